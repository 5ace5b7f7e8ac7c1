// Points on the scene's emissive triangles, drawn by power, for next-event estimation on the GPU
// (shaders/shared/EmitterPoints.h has the densities; EmitterPointPass.h shadows and uploads them).
// Host-only and deterministic: the points of (seed, iteration) never depend on the device.
#pragma once

#include "sampling/Distribution.h"
#include "scene/Scene.h"

#include <shared/EmitterPoints.h>
#include <vector>

namespace bl::gpu {

class EmitterPointSampler {
public:
    explicit EmitterPointSampler(const Scene& scene);

    bool empty() const { return mTriangles.empty(); }
    // 1 / Phi, Phi = sum over emissive triangles of mean(L_e) * area (0 without emitters).
    float inversePower() const { return mInversePower; }

    // `count` points for iteration `iteration` of run `seed`, the scene at `time`: stratified in the
    // power-CDF (point k in [k, k + 1) / count), uniform by area on the triangle chosen. Each
    // point's cube centre sits `lift` world units off the emitter along its front normal.
    std::vector<shader::GpuEmitterPoint> sample(std::uint32_t count, std::uint32_t seed, std::uint32_t iteration,
                                                double time, float lift) const;
    // One point from three numbers in [0, 1): `power` picks the triangle by the power CDF, `u` the
    // point on it (uniform by area). Its density is blEmitterAreaPdf (p_A = mean(L_e) / Phi).
    // `coordinateScale` (optional): the largest coordinate magnitude of the triangle's vertices,
    // for a ray leaving the point (EmbreeScene::offsetOrigin).
    shader::GpuEmitterPoint point(float power, glm::vec2 u, double time, float lift,
                                  float* coordinateScale = nullptr) const;

private:
    struct EmitterTriangle {
        std::uint32_t mesh;
        std::uint32_t triangle;
    };
    const Scene* mScene;
    std::vector<EmitterTriangle> mTriangles;
    Distribution1D mByPower;
    float mInversePower = 0.0f;
};

} // namespace bl::gpu
