// Mitsuba 3 XML import (core/scene/MitsubaLoader.h): what each supported element becomes, and a
// clear error naming the file and line for what is not supported. The real Mitsuba Cornell box
// against its hand-written TOML twin: tests/modes/reference/MitsubaTwinTest.cpp.
#include "image/ImageIO.h"
#include "sampling/EnvironmentLight.h"
#include "scene/MitsubaLoader.h"
#include "scene/SceneLoader.h"
#include "support/TestFiles.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>
#include <utility>

using namespace bl;
using bl::test::errorOf;
using bl::test::writeTempFile;

namespace {

const char* kSensor = R"(<sensor type="perspective">
        <float name="fov" value="$fov"/>
        <string name="fov_axis" value="smaller"/>
        <transform name="to_world"><lookat origin="0, 1, 5" target="0, 1, 0" up="0, 1, 0"/></transform>
        <film type="hdrfilm"><integer name="width" value="64"/><integer name="height" value="32"/></film>
    </sensor>)";

// A scene file `body` inside <scene>, with the sensor and a default fov.
std::string scene(const std::string& body, const std::string& name = "scene.xml") {
    return writeTempFile(name, std::string("<scene version=\"3.0.0\">\n<default name=\"fov\" value=\"40\"/>\n") +
                                   kSensor + "\n" + body + "\n</scene>\n");
}

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
    return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tolerance)));
}

} // namespace

// The sensor: the lookat pose, the film's size, "smaller" read as the axis of the film's smaller
// side (y for 64 x 32), the fov from a <default> parameter; the ignored parts said in the notes.
TEST(MitsubaLoader, SensorFilmAndParameters) {
    const Scene s = loadScene(scene(R"(<integrator type="path"/>
        <shape type="rectangle"/>)"));
    EXPECT_TRUE(near(s.camera.pose.position, {0, 1, 5}));
    EXPECT_TRUE(near(s.camera.pose.target, {0, 1, 4}));
    EXPECT_TRUE(near(s.camera.pose.up, {0, 1, 0}));
    EXPECT_EQ(s.camera.resolution, glm::ivec2(64, 32));
    EXPECT_EQ(s.camera.fovAxis, FovAxis::Y);
    EXPECT_FLOAT_EQ(s.camera.fovDegrees, 40.0f);
    EXPECT_TRUE(std::any_of(s.importNotes.begin(), s.importNotes.end(),
                            [](const std::string& n) { return n.find("integrator") != std::string::npos; }));
}

// to_world composes its operations in order (scale, then rotate, then translate here): the unit
// rectangle [-1, 1]^2 in z = 0 facing +z, scaled by 2, turned 90 degrees about x (now facing -y),
// moved up 3.
TEST(MitsubaLoader, TransformsComposeInOrder) {
    const Scene s = loadScene(scene(R"(<shape type="rectangle">
        <transform name="to_world">
            <scale value="2"/>
            <rotate x="1" angle="90"/>
            <translate y="3"/>
        </transform>
    </shape>)"));
    ASSERT_EQ(s.meshes.size(), 1u);
    const Bounds b = s.bounds();
    EXPECT_TRUE(near(b.lo, {-2, 3, -2}, 1e-4f));
    EXPECT_TRUE(near(b.hi, {2, 3, 2}, 1e-4f));
    for (const glm::vec3& n : s.meshes[0].normals) EXPECT_TRUE(near(n, {0, -1, 0}, 1e-5f));
}

// bsdfs and emitters by reference, declared after the shape and in an included file; the area
// emitter becomes the mesh's emission, a twosided bsdf its inner diffuse; a point light and a
// constant sky; analytic shapes (cube, sphere tessellated, said in the notes).
TEST(MitsubaLoader, ReferencesIncludesEmittersAndShapes) {
    writeTempFile("materials.xml", R"(<scene version="3.0.0">
        <bsdf type="twosided" id="grey"><bsdf type="diffuse"><rgb name="reflectance" value="0.2, 0.4, 0.6"/></bsdf></bsdf>
    </scene>)");
    const Scene s = loadScene(scene(R"(<shape type="cube"><ref id="grey"/><ref id="lamp"/></shape>
        <include filename="materials.xml"/>
        <emitter type="area" id="lamp"><rgb name="radiance" value="5"/></emitter>
        <shape type="sphere"><point name="center" x="0" y="4" z="0"/><float name="radius" value="0.5"/></shape>
        <emitter type="point"><point name="position" value="1, 2, 3"/><rgb name="intensity" value="7, 8, 9"/></emitter>
        <emitter type="constant"><rgb name="radiance" value="0.25"/></emitter>)"));
    ASSERT_EQ(s.meshes.size(), 2u);
    const Material& grey = s.materials.at(s.meshes[0].material);
    EXPECT_TRUE(near(grey.albedo, {0.2f, 0.4f, 0.6f}));
    EXPECT_TRUE(near(s.meshes[0].emission, glm::vec3(5.0f)));
    EXPECT_EQ(s.meshes[0].triangles.size(), 12u);
    EXPECT_TRUE(near(s.materials.at(s.meshes[1].material).albedo, glm::vec3(0.5f))); // Mitsuba's default
    EXPECT_TRUE(near(s.meshes[1].emission, glm::vec3(0.0f)));
    float top = -1e30f;
    for (const glm::vec3& p : s.meshes[1].positions) top = std::max(top, p.y);
    EXPECT_NEAR(top, 4.5f, 1e-4f);
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(near(s.lights[0].position, {1, 2, 3}));
    EXPECT_TRUE(near(s.lights[0].intensity, {7, 8, 9}));
    EXPECT_TRUE(s.environment.present);
    EXPECT_TRUE(near(s.environment.radiance, glm::vec3(0.25f)));
    EXPECT_TRUE(std::any_of(s.importNotes.begin(), s.importNotes.end(),
                            [](const std::string& n) { return n.find("sphere tessellated") != std::string::npos; }));
}

// A spot along its to_world's +z: cutoff_angle and beam_width become the cone and its edge (the
// edge's shape differs: Mitsuba's is linear in angle, ours a smoothstep in cosine; the note says
// by how much).
TEST(MitsubaLoader, SpotLightKeepsItsConeAndStatesTheEdge) {
    const Scene s = loadScene(scene(R"(<shape type="rectangle"/>
        <emitter type="spot">
            <rgb name="intensity" value="100"/>
            <float name="cutoff_angle" value="30"/>
            <transform name="to_world"><lookat origin="0, 5, 0" target="0, 0, 0" up="0, 0, 1"/></transform>
        </emitter>)"));
    ASSERT_EQ(s.lights.size(), 1u);
    const Light& l = s.lights[0];
    EXPECT_EQ(l.type, Light::Type::Spot);
    EXPECT_TRUE(near(l.position, {0, 5, 0}));
    EXPECT_TRUE(near(l.direction, {0, -1, 0}));
    EXPECT_FLOAT_EQ(l.coneAngleDegrees, 30.0f);
    EXPECT_FLOAT_EQ(l.falloffDegrees, 7.5f); // Mitsuba's default beam_width: 3/4 of the cutoff
    EXPECT_TRUE(std::any_of(s.importNotes.begin(), s.importNotes.end(),
                            [](const std::string& n) { return n.find("spot (cutoff 30") != std::string::npos; }));
}

// An envmap (a rotation about +y in to_world) looks every direction up where Mitsuba does:
// Mitsuba's envmap.cpp reads local direction v at u = atan2(v.x, -v.z) / 2 pi, v = acos(v.y) / pi,
// v = to_world^-1 d. A map that is dark but for one texel: the world direction Mitsuba sees that
// texel's centre in must find it here too, at several rotations.
TEST(MitsubaLoader, EnvironmentMapLooksUpWhereMitsubaDoes) {
    constexpr int kW = 16, kH = 8;
    constexpr double kPi = 3.14159265358979323846;
    for (const double alpha : {0.0, 30.0, -135.0}) {
        for (const glm::ivec2 texel : {glm::ivec2(3, 2), glm::ivec2(12, 5)}) {
            Image map(kW, kH);
            map.pixels()[std::size_t(texel.y * kW + texel.x)] = glm::vec3(100.0f);
            const std::string file = bl::test::tempDir() + "/sky.exr";
            writeExr(file, map);
            const Scene s = loadScene(scene("<shape type=\"rectangle\"/><emitter type=\"envmap\">"
                                            "<string name=\"filename\" value=\"" + file + "\"/>"
                                            "<transform name=\"to_world\"><rotate y=\"1\" angle=\"" +
                                            std::to_string(alpha) + "\"/></transform></emitter>"));
            // Mitsuba's local direction at the texel's centre, then to_world.
            const double u = (texel.x + 0.5) / kW, v = (texel.y + 0.5) / kH;
            const double phi = 2.0 * kPi * u, theta = kPi * v;
            const glm::dvec3 local(std::sin(phi) * std::sin(theta), std::cos(theta), -std::cos(phi) * std::sin(theta));
            const glm::dvec3 world = glm::dvec3(glm::rotate(glm::dmat4(1.0), alpha * kPi / 180.0, glm::dvec3(0, 1, 0)) *
                                                glm::dvec4(local, 0.0));
            const glm::vec3 seen = EnvironmentLight(s.environment, false).radiance(glm::vec3(world));
            EXPECT_NEAR(seen.x, 100.0f, 1e-2f) << "rotation " << alpha << ", texel " << texel.x << ", " << texel.y;
        }
    }
}

// A bitmap texture as a diffuse reflectance on an obj shape: the material's albedo texture (the
// texture is the reflectance); one texture per file; on an analytic shape it is refused.
TEST(MitsubaLoader, BitmapReflectanceOnMeshes) {
    Image red(2, 2);
    for (glm::vec3& p : red.pixels()) p = {1.0f, 0.0f, 0.0f};
    writePng(bl::test::tempDir() + "/red.png", red);
    writeTempFile("quad.obj", "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 1/1 2/2 3/3 4/4\n");
    const std::string bsdf = R"(<bsdf type="diffuse" id="painted">
            <texture type="bitmap" name="reflectance"><string name="filename" value="red.png"/></texture></bsdf>)";
    const Scene s = loadScene(scene(bsdf + R"(
        <shape type="obj"><string name="filename" value="quad.obj"/><ref id="painted"/></shape>
        <shape type="obj"><string name="filename" value="quad.obj"/><ref id="painted"/>
            <transform name="to_world"><translate z="1"/></transform></shape>)"));
    ASSERT_EQ(s.meshes.size(), 2u);
    const Material& m = s.materials.at(s.meshes[0].material);
    ASSERT_EQ(m.albedoTexture, 0);
    EXPECT_EQ(s.textures.size(), 1u);
    EXPECT_EQ(s.textures[0].image.width, 2);
    EXPECT_TRUE(near(m.albedo, glm::vec3(1.0f)));
    const std::string e = errorOf([&] { loadScene(scene(bsdf + R"(<shape type="rectangle"><ref id="painted"/></shape>)",
                                                        "analytic.xml")); });
    EXPECT_NE(e.find("textured bsdf on an analytic shape"), std::string::npos) << e;
}

// A shapegroup drawn by two instances: its shapes copied into the scene, each placed by the
// instance's to_world after its own.
TEST(MitsubaLoader, InstancesPlaceTheirGroupsShapes) {
    const Scene s = loadScene(scene(R"(<shape type="shapegroup" id="pair">
            <shape type="cube"><transform name="to_world"><scale value="0.5"/></transform></shape>
            <shape type="rectangle"><transform name="to_world"><translate z="2"/></transform></shape>
        </shape>
        <shape type="instance"><ref id="pair"/><transform name="to_world"><translate x="10"/></transform></shape>
        <shape type="instance"><ref id="pair"/><transform name="to_world"><translate x="-10"/></transform></shape>)"));
    ASSERT_EQ(s.meshes.size(), 4u);
    const Bounds b = s.bounds();
    EXPECT_TRUE(near(b.lo, {-11, -1, -0.5f}, 1e-4f));
    EXPECT_TRUE(near(b.hi, {11, 1, 2}, 1e-4f));
}

// Details where a careless reading would silently differ from Mitsuba (a review against its
// sources): a top-level emitter with an id is still in the scene; a named <ref name="bsdf"> is a
// reference; a lookat without up takes Mitsuba's coordinate_system (+x when looking down -z); a
// mirroring to_world keeps the emitting side where the normals say (Mitsuba's flip_normals is a
// scale of -1 in z: the rectangle then emits toward -z); a mesh without normals gets smooth ones.
TEST(MitsubaLoader, SilentDifferencesFromMitsubaAreAvoided) {
    // The OBJ names an MTL library our MTL reader refuses (Kd above 1): Mitsuba ignores MTL files,
    // so must the importer.
    writeTempFile("bent.mtl", "newmtl paint\nKd 1.5 0 0\n");
    writeTempFile("bent.obj", "mtllib bent.mtl\nusemtl paint\nv 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 1\nf 1 2 3\nf 1 3 4\n");
    const Scene s = loadScene(writeTempFile("details.xml", R"(<scene version="3.0.0">
        <sensor type="perspective"><float name="fov" value="30"/>
            <transform name="to_world"><lookat origin="0, 0, 5" target="0, 0, 0"/></transform></sensor>
        <emitter type="point" id="bulb"><point name="position" value="0, 2, 0"/></emitter>
        <bsdf type="diffuse" id="dark"><rgb name="reflectance" value="0.1"/></bsdf>
        <shape type="rectangle"><ref name="bsdf" id="dark"/>
            <emitter type="area"><rgb name="radiance" value="1"/></emitter>
            <transform name="to_world"><scale z="-1"/></transform></shape>
        <shape type="obj"><string name="filename" value="bent.obj"/></shape>
    </scene>)"));
    ASSERT_EQ(s.lights.size(), 1u);
    EXPECT_TRUE(near(s.lights[0].position, {0, 2, 0}));
    EXPECT_TRUE(near(s.camera.pose.up, {1, 0, 0}));
    ASSERT_EQ(s.meshes.size(), 2u);
    EXPECT_TRUE(near(s.materials.at(s.meshes[0].material).albedo, glm::vec3(0.1f)));
    const Mesh& r = s.meshes[0];
    for (const glm::uvec3& t : r.triangles) {
        const glm::vec3 face = glm::cross(r.positions[t.y] - r.positions[t.x], r.positions[t.z] - r.positions[t.x]);
        EXPECT_LT(face.z, 0.0f) << "the front (emitting) side must face -z";
    }
    // The two triangles of the bent quad share the vertices of their common edge with one
    // averaged normal: not the flat normal of either.
    const Mesh& bent = s.meshes[1];
    const glm::vec3 shared = glm::normalize(bent.normals.at(0));
    EXPECT_GT(std::abs(shared.y), 1e-3f) << "smooth normals expected";
}

// What is not supported is refused with the file, the line and what is supported; never a
// silently different scene.
// roughplastic as Lambert + Phong with its Fresnel factors at normal incidence: int_ior 1.5 over
// ext_ior 1 gives F0 = 0.04 as the lobe's reflectance, the diffuse base times (1 - F0)^2 / (eta^2
// (1 - F_int)) with F_int = 0.5967 by Egan and Hilgeman's fit (-1.440/eta^2 + 0.710/eta + 0.668 +
// 0.0636 eta, within 0.1% of the integral; the loader integrates it), and alpha 0.1 the mirror-
// direction exponent (2 / 0.01 - 2) / 4 = 49.5; the approximation is said in the notes.
TEST(MitsubaLoader, RoughPlasticMapsToLambertAndPhong) {
    const Scene s = loadScene(scene(R"(<shape type="rectangle"><bsdf type="roughplastic">
            <rgb name="diffuse_reflectance" value="0.5, 0.25, 0.1"/><float name="int_ior" value="1.5"/>
            <float name="ext_ior" value="1"/><float name="alpha" value="0.1"/></bsdf></shape>)"));
    const Material& m = s.materials.at(s.meshes.at(0).material);
    const double eta = 1.5, fInternal = -1.440 / (eta * eta) + 0.710 / eta + 0.668 + 0.0636 * eta;
    const double factor = (1.0 - 0.04) * (1.0 - 0.04) / (eta * eta * (1.0 - fInternal));
    EXPECT_NEAR(m.albedo.x, 0.5 * factor, 0.002 * 0.5 * factor);
    EXPECT_NEAR(m.albedo.z, 0.1 * factor, 0.002 * 0.1 * factor);
    EXPECT_TRUE(near(m.specular, glm::vec3(0.04f), 1e-6f));
    EXPECT_FLOAT_EQ(m.exponentU, 49.5f);
    EXPECT_FLOAT_EQ(m.exponentV, 49.5f);
    EXPECT_TRUE(std::any_of(s.importNotes.begin(), s.importNotes.end(),
                            [](const std::string& n) { return n.find("Fresnel held at normal incidence") != std::string::npos; }));
    const std::string e = errorOf([] {
        loadScene(scene(R"(<shape type="rectangle"><bsdf type="roughplastic"><boolean name="nonlinear" value="true"/></bsdf></shape>)",
                        "nonlinear.xml"));
    });
    EXPECT_NE(e.find("nonlinear = true is not supported"), std::string::npos) << e;
}

// Veach's multiple importance sampling scene (Mitsuba's, ../shared): its four roughplastic plates
// (alpha 0.005, 0.02, 0.05, 0.1) load as Phong lobes of exponent 19999.5, 1249.5, 199.5, 49.5.
TEST(MitsubaLoader, VeachMisPlatesLoadAsPhongLobes) {
    BL_SKIP_WITHOUT_SHARED("data/glossy/veach-mis/veach_mis.xml");
    const Scene s = loadScene(bl::test::sharedPath("data/glossy/veach-mis/veach_mis.xml"));
    std::vector<float> exponents;
    for (const Material& m : s.materials) {
        if (m.glossy()) exponents.push_back(m.exponentU);
    }
    std::sort(exponents.begin(), exponents.end());
    ASSERT_EQ(exponents.size(), 4u);
    EXPECT_FLOAT_EQ(exponents[0], 49.5f);
    EXPECT_FLOAT_EQ(exponents[1], 199.5f);
    EXPECT_FLOAT_EQ(exponents[2], 1249.5f);
    EXPECT_FLOAT_EQ(exponents[3], 19999.5f);
}

TEST(MitsubaLoader, UnsupportedElementsAreErrorsWithFileAndLine) {
    const auto refusal = [](const std::string& body) { return errorOf([&] { loadScene(scene(body, "bad.xml")); }); };
    // The body starts on line 9 of the file (after <scene>, the default and the 6-line sensor).
    std::string e = refusal("<shape type=\"hair\"/>");
    EXPECT_NE(e.find("bad.xml:9: <shape type=\"hair\">"), std::string::npos) << e;
    EXPECT_NE(e.find("supported: obj, ply, rectangle, cube, disk, sphere, shapegroup, instance"), std::string::npos) << e;
    const std::pair<const char*, const char*> cases[] = {
        {"<shape type=\"rectangle\"><bsdf type=\"roughconductor\"/></shape>", "bsdf type not supported"},
        {"<shape type=\"rectangle\"><ref id=\"nowhere\"/></shape>", "no element with id 'nowhere'"},
        {"<shape type=\"rectangle\"><float name=\"radius\" value=\"1\"/></shape>", "not supported here"},
        {"<emitter type=\"directional\"/>", "emitter type not supported"},
        {"<shape type=\"rectangle\"><transform name=\"to_world\"><skew/></transform></shape>",
         "transform operation not supported"},
        {"<shape type=\"sphere\"><float name=\"radius\" value=\"$missing\"/></shape>", "'$missing' has no <default>"},
        {"<emitter type=\"point\"><rgb name=\"intensity\" value=\"1e39\"/></emitter>", "more than a 32-bit float holds"},
        {"<emitter type=\"constant\"><rgb name=\"radiance\" value=\"1, -5, 1\"/></emitter>", "value -5 is negative"},
        {"<shape type=\"sphere\"><transform name=\"to_world\"><scale x=\"2\"/></transform></shape>",
         "a sphere's to_world must scale uniformly"},
        {"<emitter type=\"point\"><point name=\"position\" value=\"0, 0, 0\"/>"
         "<transform name=\"to_world\"><translate x=\"1\"/></transform></emitter>",
         "not both"},
    };
    for (const auto& [body, expected] : cases) {
        e = refusal(body);
        EXPECT_NE(e.find(expected), std::string::npos) << e;
    }
    e = errorOf([] { loadScene(writeTempFile("broken.xml", "<scene>\n<shape type=\"cube\">\n</scene>\n")); });
    EXPECT_NE(e.find("broken.xml:"), std::string::npos) << e;
    e = errorOf([] {
        loadScene(writeTempFile("scaled.xml", "<scene><sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/>"
                                              "<transform name=\"to_world\"><scale value=\"2\"/></transform></sensor>"
                                              "<shape type=\"cube\"/></scene>"));
    });
    EXPECT_NE(e.find("may not scale"), std::string::npos) << e;
    e = errorOf([] {
        loadScene(writeTempFile("film.xml", "<scene><sensor type=\"perspective\"><float name=\"fov\" value=\"30\"/>"
                                            "<film type=\"hdrfilm\"><integer name=\"width\" value=\"64.5\"/></film>"
                                            "</sensor><shape type=\"cube\"/></scene>"));
    });
    EXPECT_NE(e.find("must be an integer, got 64.5"), std::string::npos) << e;
    e = errorOf([] { loadScene(writeTempFile("nocamera.xml", "<scene><shape type=\"cube\"/></scene>")); });
    EXPECT_NE(e.find("no <sensor"), std::string::npos) << e;
}
