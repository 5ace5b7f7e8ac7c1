#include "scene/Camera.h"

#include <gtest/gtest.h>
#include <shared/Camera.h>

using namespace bl;

// The published Cornell camera: right = normalize(cross(forward, up)) points to -x, so the red
// wall (x ~ 556) is on the left of the image.
TEST(Camera, CornellBasisPutsPlusXOnTheLeft) {
    Camera cam;
    cam.pose = {{278, 273, -800}, {278, 273, 0}, {0, 1, 0}};
    cam.fovDegrees = 39.3077f;
    shader::GpuCamera g = makeGpuCamera(cam, 0.0, 1.0f);
    EXPECT_NEAR(g.right.x, -1.0f, 1e-6f);
    EXPECT_NEAR(g.up.y, 1.0f, 1e-6f);
    glm::vec4 clip = g.viewProj * glm::vec4(550.0f, 273.0f, 300.0f, 1.0f);
    EXPECT_LT(clip.x / clip.w, 0.0f); // left half of the image
}

// Rasterization (viewProj) and ray generation (blCameraRayDirection) agree pixel for pixel.
TEST(Camera, ProjectionMatchesRayGeneration) {
    Camera cam;
    cam.pose = {{1, 2, 3}, {-2, 0.5f, -1}, {0, 1, 0.2f}};
    cam.fovDegrees = 50.0f;
    cam.fovAxis = FovAxis::Y;
    cam.resolution = {320, 200};
    shader::GpuCamera g = makeGpuCamera(cam, 0.0, 0.01f);
    for (glm::vec2 p : {glm::vec2(0.5f, 0.5f), glm::vec2(319.5f, 10.25f), glm::vec2(160, 100), glm::vec2(3, 199)}) {
        glm::vec3 d = shader::blCameraRayDirection(g, p);
        glm::vec4 clip = g.viewProj * glm::vec4(g.position + 7.0f * d, 1.0f);
        glm::vec2 ndc = glm::vec2(clip) / clip.w;
        glm::vec2 pixel = (ndc * 0.5f + 0.5f) * glm::vec2(320, 200);
        EXPECT_NEAR(pixel.x, p.x, 1e-3f);
        EXPECT_NEAR(pixel.y, p.y, 1e-3f);
        EXPECT_GT(clip.z / clip.w, 0.0f); // in front: reversed depth in (0, 1]
        EXPECT_LE(clip.z / clip.w, 1.0f);
    }
    EXPECT_NEAR(g.tanHalfY, std::tan(glm::radians(25.0f)), 1e-6f);
    EXPECT_NEAR(g.tanHalfX / g.tanHalfY, 320.0f / 200.0f, 1e-5f);
}

TEST(Camera, KeyframesInterpolate) {
    Camera cam;
    cam.keys = {{0.0, {{0, 0, 0}, {0, 0, -1}, {0, 1, 0}}}, {2.0, {{4, 0, 0}, {4, 0, -1}, {0, 1, 0}}}};
    EXPECT_TRUE(cam.animated());
    EXPECT_NEAR(cam.poseAt(1.0).position.x, 2.0f, 1e-6f);
    EXPECT_NEAR(cam.poseAt(5.0).position.x, 4.0f, 1e-6f);
    EXPECT_NEAR(cam.poseAt(-1.0).position.x, 0.0f, 1e-6f);
}
