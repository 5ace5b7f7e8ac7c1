// Mode bidir's spatio-temporal interleaved sampling ([TO12s] A; definitions shared with the
// shaders in shaders/modes/bidir/Interleave.h).
//
// Spatial (interleave = n > 1): the evaluation runs in the split layout, each of the n x n
// sub-images with every n^2-th of the frame's K pairs, writes its layers to the frame image at the
// pixel it shades (gather), and the resolve pass (shaders/modes/bidir/interleave.comp.glsl) blurs
// the indirect layers over the n x n neighbourhood with normal and depth weights from the G-buffer
// (interleave_filter = on) before adding the sample to the accumulator.
// Temporal (temporal = on): 2 x 2 sub-pixel caches of the (filtered) indirect light; update u
// renders sub-pixel c = u mod 4 with the c-th sample set (sequence indices c K .. c K + K - 1:
// periodic, so a fully cached static view stops changing) and overwrites cache c; every pixel is
// reconstructed from all four caches by reverse reprojection into the camera each was rendered
// with, weighted by the log-depth Gaussian (2 sigma^2 = 1e-4). Caches and the update counter live
// across setScene (frames of an animation) while the image size stays.
#pragma once

#include "gpu/CameraPass.h"
#include "image/Image.h"
#include "vk/Buffer.h"
#include "vk/BoundSet.h"
#include "vk/GpuImage.h"
#include "vk/GpuTimer.h"
#include "vk/ComputePass.h"

#include <cstdint>
#include <modes/bidir/Interleave.h>

namespace bl {

struct InterleaveOptions {
    std::uint32_t n = 1;     // sub-images per side (1: off)
    bool filter = true;      // geometry-aware blur of the gathered indirect light
    bool temporal = false;   // 2 x 2 sub-pixel caches with reverse reprojection
    bool reproject = true;   // warp into each cache's camera (false: static camera, identity warp)
    float twoSigma2 = 1e-4f; // 2 sigma^2 of the log-depth Gaussian ([TO12s] Eq. 3)
};

class Interleaving {
public:
    Interleaving(const vk::Context& ctx, std::uint32_t width, std::uint32_t height, const InterleaveOptions& options);

    // Whether the evaluation hands its layers to this pass (else it accumulates them itself).
    bool active() const { return mOptions.n > 1 || mOptions.temporal; }
    const InterleaveOptions& options() const { return mOptions; }
    bool matches(std::uint32_t width, std::uint32_t height, const InterleaveOptions& o) const;
    void setReproject(bool reproject) { mOptions.reproject = reproject; }

    // The resolve pipeline against this setScene's camera set layout.
    void preparePipeline(VkDescriptorSetLayout cameraSetLayout);
    // Where the evaluation writes its layers (a 1 x 1 stand-in when inactive).
    VkImageView frameView() const { return mFrame.view(); }
    // The evaluation's InterleaveEvaluate record (n, output).
    VkBuffer evaluateBuffer() const { return mEvaluate.get(); }
    // The evaluation's dispatch size: the split layout covers n x n blocks of ceil(size / n).
    std::uint32_t dispatchWidth() const;
    std::uint32_t dispatchHeight() const;

    // First sequence index of this frame's K pairs: iteration K, or with temporal caches the fixed
    // set of the cache this update rewrites.
    std::uint64_t sequenceBase(std::uint32_t iteration, std::uint32_t pairs) const;
    // The camera sample of this frame: with temporal caches the centre of the updated sub-pixel.
    gpu::CameraSample cameraSample(const gpu::CameraSample& jittered, std::uint32_t width, std::uint32_t height) const;

    // Before the evaluation: marks every pixel of the frame image dropped until written.
    void recordClear(VkCommandBuffer cmd) const;
    // After it: blur, caches, reconstruction, accumulation. `camera` is this frame's.
    void recordResolve(VkCommandBuffer cmd, VkDescriptorSet cameraSet, const shader::GpuCamera& camera,
                       vk::GpuTimer* timer);
    // Once per frame after the submit: the next update rewrites the next cache.
    void advance() { ++mUpdates; }
    // The last frame's cache-hit ratio per pixel (grey; shaders/modes/bidir/Interleave.h
    // kTemporalHitsLayer says what it is); black without temporal caches.
    Image cacheHits() const;

private:
    const vk::Context* mContext;
    std::uint32_t mWidth, mHeight;
    InterleaveOptions mOptions;
    std::uint64_t mUpdates = 0;
    vk::GpuImage mFrame;
    vk::GpuImage mCaches;
    vk::Buffer mCacheInfo;
    vk::Buffer mEvaluate;
    vk::BoundSet mBound;
    vk::ComputePass<shader::InterleavePush> mFilter;
};

} // namespace bl
