#include "scene/SceneLoader.h"

#include "base/Error.h"
#include "base/Log.h"
#include "config/StrictToml.h"
#include "image/ImageIO.h"
#include "scene/MeshCleanup.h"
#include "scene/MeshFile.h"
#include "scene/MeshTransform.h"
#include "scene/GltfLoader.h"
#include "scene/MitsubaLoader.h"
#include "scene/MtlLoader.h"
#include "scene/ScenePrecision.h"
#include "scene/ShaderConversions.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <glm/gtc/matrix_transform.hpp>
#include <limits>
#include <map>
#include <set>
#include <variant>

namespace fs = std::filesystem;

namespace bl {
namespace {

// Largest Phong / Ashikhmin-Shirley exponent: beyond it the lobe is a mirror in float precision.
constexpr double kMaxExponent = 1.0e6;

std::string resolveFile(StrictTable& t, const std::string& key) {
    std::string name = t.string(key);
    fs::path base = fs::path(t.file()).parent_path();
    fs::path p = base / name;
    if (!fs::is_regular_file(p)) {
        t.fail(key, "file '" + name + "' not found (looked for " + p.string() + ")");
    }
    return p.string();
}

// Radiometric values (intensity, emission, radiance, albedo, scale) reach the GPU and the
// reference as 32-bit floats. A value a float cannot hold would render black or NaN in every mode
// without a word (1e39 becomes inf; 1e-39 becomes a denormal the GPU flushes to 0), so it is
// refused here with the value as typed.
double requireFloat(StrictTable& t, const std::string& key, double v) {
    if (std::abs(v) > double(std::numeric_limits<float>::max())) {
        t.fail(key, "value " + formatNumber(v) + " is beyond the largest 32-bit float (" +
                        formatNumber(std::numeric_limits<float>::max()) + ")");
    }
    if (v != 0.0 && std::abs(v) < double(std::numeric_limits<float>::min())) {
        t.fail(key, "value " + formatNumber(v) + " is below the smallest normal 32-bit float (" +
                        formatNumber(std::numeric_limits<float>::min()) + "): use 0 or a larger value");
    }
    return v;
}

glm::vec3 floatVec3(StrictTable& t, const std::string& key) {
    const std::vector<double> v = t.numbers(key, 3);
    for (double x : v) requireFloat(t, key, x);
    return {float(v[0]), float(v[1]), float(v[2])};
}

glm::vec3 floatVec3(StrictTable& t, const std::string& key, glm::vec3 fallback) {
    return t.has(key) ? floatVec3(t, key) : fallback;
}

// A product of two representable values (radiance times scale) must be representable too.
void requireFloatProduct(StrictTable& t, const std::string& key, float a, float b, const std::string& what) {
    const double product = double(a) * double(b);
    if (product > double(std::numeric_limits<float>::max())) {
        char text[32];
        std::snprintf(text, sizeof(text), "%.3g", product);
        t.fail(key, what + ": " + formatNumber(a) + " x " + formatNumber(b) + " = " + text +
                        " is beyond the largest 32-bit float (" + formatNumber(std::numeric_limits<float>::max()) +
                        ")");
    }
}

void requireRange(StrictTable& t, const std::string& key, glm::vec3 v, float lo, float hi) {
    for (int i = 0; i < 3; ++i) {
        if (v[i] < lo || v[i] > hi) {
            t.fail(key, "value " + formatNumber(v[i]) + " outside [" + formatNumber(lo) + ", " +
                            formatNumber(hi) + "]");
        }
    }
}

void requireNonNegative(StrictTable& t, const std::string& key, glm::vec3 v) {
    for (int i = 0; i < 3; ++i) {
        if (v[i] < 0.0f) {
            t.fail(key, "value " + formatNumber(v[i]) + " is negative");
        }
    }
}

// A spot's lit solid angle is proportional to 1 - cos of its cone, which the GPU and the reference
// hold as a float a whole number of steps (2^-24) below 1 and compare with a dot product rounded to
// the same steps: it comes out up to one step off, a relative error of 1 / spotConeSteps. Measured
// (raster and reference alike, lit fraction of a view just wider than the cone): 0.01 degrees
// renders black, 0.03 -32 %, 0.05 -13 %, 0.1 and wider within 1 %.
constexpr double kWarnConeSteps = 100.0; // up to 1 % off: a warning (half-angle under ~0.2 degrees)
void requireRenderableCone(StrictTable& t, float coneDegrees) {
    const double steps = spotConeSteps(coneDegrees);
    const std::string what = "cone_angle " + formatNumber(coneDegrees) + " degrees: its cosine is " +
                             formatNumber(steps) + " float steps (2^-24) below 1";
    if (steps < kMinSpotConeSteps) { // up to 10 % off: refused (half-angle under ~0.063 degrees)
        t.fail("cone_angle", what + ", so 32-bit floats render its lit area up to " +
                                 (steps < 1.0 ? std::string("100 % off (black)") : formatNumber(100.0 / steps) + " % off") +
                                 "; the narrowest cone rendered within 10 % is about 0.063 degrees");
    }
    if (steps < kWarnConeSteps) {
        log::warn(t.file() + ":" + std::to_string(t.line("cone_angle")) + ": " + what + ": its lit area may be up to " +
                  formatNumber(100.0 / steps) + " % off (1 % needs about 0.2 degrees)");
    }
}

glm::vec3 unitDirection(StrictTable& t, const std::string& key, glm::vec3 v) {
    float len = glm::length(v);
    if (!(len > 0.0f)) {
        t.fail(key, "direction must not be zero");
    }
    return v / len;
}

CameraPose readPose(StrictTable& t, const CameraPose& fallback) {
    CameraPose p;
    p.position = t.vec3("position", fallback.position);
    p.target = t.vec3("target", fallback.target);
    p.up = t.vec3("up", fallback.up);
    glm::vec3 forward = p.target - p.position;
    if (!(glm::length(forward) > 0.0f)) {
        t.fail("target", "camera target equals its position");
    }
    if (!(glm::length(glm::cross(glm::normalize(forward), p.up)) > 1e-6f)) {
        t.fail("up", "up vector is zero or parallel to the viewing direction");
    }
    return p;
}

std::vector<double> readKeyTimes(std::vector<StrictTable>& keys) {
    std::vector<double> times;
    for (StrictTable& k : keys) {
        double time = k.number("time");
        if (!times.empty() && time <= times.back()) {
            k.fail("time", "keyframe times must increase (" + formatNumber(time) + " after " +
                               formatNumber(times.back()) + ")");
        }
        times.push_back(time);
    }
    return times;
}

void readCamera(StrictTable& t, Camera& cam) {
    cam.pose = readPose(t, cam.pose);
    cam.fovDegrees = static_cast<float>(t.number("fov", cam.fovDegrees));
    if (!(cam.fovDegrees > 0.0f && cam.fovDegrees < 180.0f)) {
        t.fail("fov", "value " + formatNumber(cam.fovDegrees) + " outside (0, 180) degrees");
    }
    std::string axis = t.string("fov_axis", "x");
    if (axis != "x" && axis != "y") {
        t.fail("fov_axis", "expected \"x\" or \"y\", got \"" + axis + "\"");
    }
    cam.fovAxis = axis == "x" ? FovAxis::X : FovAxis::Y;
    if (t.has("resolution")) {
        cam.resolution = t.ivec2("resolution");
        for (int i = 0; i < 2; ++i) {
            if (cam.resolution[i] <= 0 || cam.resolution[i] > kMaxResolution) {
                t.fail("resolution", "value " + std::to_string(cam.resolution[i]) + " outside [1, " +
                                         std::to_string(kMaxResolution) + "]");
            }
        }
    }
    std::vector<StrictTable> keys = t.tables("keyframe");
    std::vector<double> times = readKeyTimes(keys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        cam.keys.push_back({times[i], readPose(keys[i], cam.pose)});
        keys[i].finish();
    }
    t.finish();
}

Material readMaterial(StrictTable& t, std::vector<Texture>& textures) {
    Material m;
    m.name = t.string("name");
    m.albedo = floatVec3(t, "albedo", m.albedo);
    requireRange(t, "albedo", m.albedo, 0.0f, 1.0f);
    m.specular = floatVec3(t, "specular", m.specular);
    requireRange(t, "specular", m.specular, 0.0f, 1.0f);
    for (int i = 0; i < 3; ++i) {
        if (m.albedo[i] + m.specular[i] > 1.0f + 1e-6f) {
            log::warn(t.file() + ":" + std::to_string(t.line("specular")) + ": material '" + m.name +
                      "': albedo + specular > 1 reflects more energy than it receives");
            break;
        }
    }
    auto exponent = [&](const std::string& key, double fallback) {
        double e = t.number(key, fallback);
        if (!(e > 0.0 && e <= kMaxExponent)) {
            t.fail(key, "value " + formatNumber(e) + " outside (0, " + formatNumber(kMaxExponent) + "]");
        }
        return static_cast<float>(e);
    };
    if (t.has("exponent") && (t.has("exponent_u") || t.has("exponent_v"))) {
        t.fail("exponent", "give either exponent or exponent_u/exponent_v, not both");
    }
    m.exponentU = m.exponentV = exponent("exponent", 1.0);
    if (t.has("exponent_u") || t.has("exponent_v")) {
        m.exponentU = exponent("exponent_u", 1.0);
        m.exponentV = exponent("exponent_v", m.exponentU);
    }
    if (t.has("albedo_texture")) {
        std::string path = resolveFile(t, "albedo_texture");
        m.albedoTexture = static_cast<int>(textures.size());
        textures.push_back({path, readRgba8(path)});
    }
    t.finish();
    return m;
}

glm::mat4 readStaticTransform(StrictTable& t) {
    glm::vec3 translate = t.vec3("translate", glm::vec3(0.0f));
    glm::vec3 rotate = t.vec3("rotate", glm::vec3(0.0f));
    glm::vec3 scale(1.0f);
    if (t.has("scale")) {
        scale = t.isArray("scale") ? t.vec3("scale") : glm::vec3(static_cast<float>(t.number("scale")));
        for (int i = 0; i < 3; ++i) {
            if (!(scale[i] > 0.0f)) {
                t.fail("scale", "value " + formatNumber(scale[i]) + " must be positive");
            }
        }
    }
    glm::mat4 m = glm::translate(glm::mat4(1.0f), translate) * glm::mat4_cast(rotationFromEulerDegrees(rotate)) *
                  glm::scale(glm::mat4(1.0f), scale);
    return m;
}

// MTL material name -> index of the scene material that replaces it (a [[mesh]]'s `materials`).
using MaterialRemap = std::map<std::string, std::uint32_t>;

void addMeshFile(Scene& scene, MeshFile file, const std::string& context,
                 const std::optional<std::uint32_t>& materialOverride, const MaterialRemap& remap,
                 const std::optional<glm::vec3>& emissionOverride, const glm::mat4& transform,
                 const RigidAnimation& animation, const NormalOptions& normals) {
    const int textureBase = static_cast<int>(scene.textures.size());
    // The scene material of each file material: remapped ones are not added, so that no unused
    // material counts in the scene's features.
    std::vector<std::uint32_t> sceneMaterialOf(file.materials.size());
    if (!materialOverride) {
        for (std::size_t i = 0; i < file.materials.size(); ++i) {
            Material& m = file.materials[i];
            if (auto it = remap.find(m.name); it != remap.end()) {
                sceneMaterialOf[i] = it->second;
                continue;
            }
            if (m.albedoTexture >= 0) {
                m.albedoTexture += textureBase;
            }
            sceneMaterialOf[i] = static_cast<std::uint32_t>(scene.materials.size());
            scene.materials.push_back(m);
        }
        for (Texture& t : file.textures) {
            scene.textures.push_back(std::move(t));
        }
    }
    scene.inputFiles.insert(scene.inputFiles.end(), file.materialFiles.begin(), file.materialFiles.end());
    for (Mesh& mesh : file.meshes) {
        bakeTransform(mesh, transform);
        CleanupStats stats = cleanupMesh(mesh, normals);
        scene.loadStats.degenerateTriangles += stats.degenerateTriangles;
        scene.loadStats.duplicateTriangles += stats.duplicateTriangles;
        scene.loadStats.repairedNormals += stats.repairedNormals;
        scene.loadStats.meshesWithGeneratedNormals += stats.generatedNormals;
        if (stats.degenerateTriangles || stats.duplicateTriangles) {
            log::debug(context + ": " + mesh.name + ": dropped " + std::to_string(stats.degenerateTriangles) +
                      " degenerate and " + std::to_string(stats.duplicateTriangles) + " duplicate triangles");
        }
        if (mesh.triangles.empty()) {
            continue;
        }
        mesh.material = materialOverride ? *materialOverride : sceneMaterialOf.at(mesh.material);
        if (emissionOverride) {
            mesh.emission = *emissionOverride;
        }
        mesh.animation = animation;
        scene.meshes.push_back(std::move(mesh));
    }
}

// One entry of a [[mesh]]'s `materials = { mtlName = "scene material" }`, with where it was written.
struct MaterialRemapEntry {
    std::string mtlName;
    std::uint32_t sceneMaterial = 0;
    std::string where; // "file:line: mesh[i].materials.name"
};

std::vector<MaterialRemapEntry> readMaterialRemap(StrictTable& t,
                                                  const std::map<std::string, std::uint32_t>& materialOf) {
    std::vector<MaterialRemapEntry> out;
    for (const StrictTable::Entry& e : t.entries("materials")) {
        const std::string where = t.file() + ":" + std::to_string(e.line) + ": " + t.context() + ".materials." + e.key;
        const std::string* name = e.isArray ? nullptr : std::get_if<std::string>(&e.values.front());
        if (!name) {
            throw Error(where + ": expected the name of a [[material]] (a string)");
        }
        auto it = materialOf.find(*name);
        if (it == materialOf.end()) {
            throw Error(where + ": no [[material]] named '" + *name + "'");
        }
        out.push_back({e.key, it->second, where});
    }
    return out;
}

// Every remapped name must be a material of the mesh file: a typo must not silently keep the MTL's.
MaterialRemap checkMaterialRemap(const std::vector<MaterialRemapEntry>& entries, const MeshFile& file,
                                 const std::string& meshPath) {
    MaterialRemap remap;
    for (const MaterialRemapEntry& e : entries) {
        auto has = [&](const Material& m) { return m.name == e.mtlName; };
        if (std::none_of(file.materials.begin(), file.materials.end(), has)) {
            std::vector<std::string> names;
            for (const Material& m : file.materials) {
                names.push_back(m.name);
            }
            std::sort(names.begin(), names.end());
            std::string list;
            for (const std::string& n : names) {
                list += (list.empty() ? "" : ", ") + n;
            }
            throw Error(e.where + ": " + fs::path(meshPath).filename().string() + " has no MTL material '" +
                        e.mtlName + "' (it has: " + (list.empty() ? "none" : list) + ")");
        }
        remap[e.mtlName] = e.sceneMaterial;
    }
    return remap;
}

// A [[mesh]]'s `normals` ("file", "flat" or "smooth") and, for "smooth", `crease_angle` (degrees).
NormalOptions readNormals(StrictTable& t) {
    NormalOptions n;
    const std::string source = t.string("normals", "file");
    if (source != "file" && source != "flat" && source != "smooth") {
        t.fail("normals", "expected \"file\", \"flat\" or \"smooth\", got \"" + source + "\"");
    }
    n.source = source == "flat" ? NormalSource::Flat : source == "smooth" ? NormalSource::Smooth : NormalSource::File;
    if (t.has("crease_angle")) {
        if (n.source != NormalSource::Smooth) {
            t.fail("crease_angle", "only with normals = \"smooth\" (normals is \"" + source + "\")");
        }
        const double crease = t.number("crease_angle");
        if (!(crease > 0.0 && crease <= 180.0)) {
            t.fail("crease_angle", "value " + formatNumber(crease) + " outside (0, 180] degrees");
        }
        n.creaseDegrees = static_cast<float>(crease);
    }
    return n;
}

void readMesh(StrictTable& t, Scene& scene, const std::map<std::string, std::uint32_t>& materialOf) {
    std::string path = resolveFile(t, "file");
    std::optional<std::uint32_t> material;
    if (t.has("material")) {
        std::string name = t.string("material");
        auto it = materialOf.find(name);
        if (it == materialOf.end()) {
            t.fail("material", "no [[material]] named '" + name + "'");
        }
        material = it->second;
    }
    if (material && t.has("materials")) {
        t.fail("materials", "give either material or materials, not both");
    }
    const std::vector<MaterialRemapEntry> remapEntries = readMaterialRemap(t, materialOf);
    std::optional<glm::vec3> emission;
    if (t.has("emission")) {
        emission = floatVec3(t, "emission");
        requireNonNegative(t, "emission", *emission);
    }
    glm::mat4 transform = readStaticTransform(t);
    const NormalOptions normals = readNormals(t);
    RigidAnimation animation;
    std::vector<StrictTable> keys = t.tables("keyframe");
    std::vector<double> times = readKeyTimes(keys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        RigidKeyframe k;
        k.time = times[i];
        k.translate = keys[i].vec3("translate", glm::vec3(0.0f));
        k.rotation = rotationFromEulerDegrees(keys[i].vec3("rotate", glm::vec3(0.0f)));
        animation.addKey(k);
        keys[i].finish();
    }
    t.finish();
    MeshFile file;
    scene.inputFiles.push_back(path); // listed even where cleanup drops every triangle
    try {
        file = loadMeshFile(path);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + "\n  (loaded from " + t.file() + ":" + std::to_string(t.line("file")) + ")");
    }
    const MaterialRemap remap = checkMaterialRemap(remapEntries, file, path);
    addMeshFile(scene, std::move(file), t.file(), material, remap, emission, transform, animation, normals);
}

Light readLight(StrictTable& t) {
    Light l;
    std::string type = t.string("type", "point");
    if (type != "point" && type != "spot") {
        t.fail("type", "expected \"point\" or \"spot\", got \"" + type + "\"");
    }
    l.type = type == "point" ? Light::Type::Point : Light::Type::Spot;
    l.position = t.vec3("position");
    l.intensity = floatVec3(t, "intensity");
    requireNonNegative(t, "intensity", l.intensity);
    if (l.type == Light::Type::Spot) {
        l.direction = unitDirection(t, "direction", t.vec3("direction"));
        l.coneAngleDegrees = static_cast<float>(t.number("cone_angle"));
        if (!(l.coneAngleDegrees > 0.0f && l.coneAngleDegrees <= 180.0f)) {
            t.fail("cone_angle", "value " + formatNumber(l.coneAngleDegrees) + " outside (0, 180] degrees");
        }
        requireRenderableCone(t, l.coneAngleDegrees);
        l.falloffDegrees = static_cast<float>(t.number("falloff", 0.0));
        if (!(l.falloffDegrees >= 0.0f && l.falloffDegrees <= l.coneAngleDegrees)) {
            t.fail("falloff", "value " + formatNumber(l.falloffDegrees) + " outside [0, cone_angle]");
        }
    }
    std::vector<StrictTable> keys = t.tables("keyframe");
    std::vector<double> times = readKeyTimes(keys);
    for (std::size_t i = 0; i < keys.size(); ++i) {
        LightKeyframe k;
        k.time = times[i];
        k.position = keys[i].vec3("position", l.position);
        if (l.type == Light::Type::Spot) {
            k.direction = keys[i].has("direction") ? unitDirection(keys[i], "direction", keys[i].vec3("direction"))
                                                   : l.direction;
        }
        l.keys.push_back(k);
        keys[i].finish();
    }
    t.finish();
    return l;
}

void readEnvironment(StrictTable& t, Environment& env) {
    env.present = true;
    if (t.has("file") == t.has("radiance")) {
        t.fail("", "give exactly one of 'file' or 'radiance'");
    }
    if (t.has("file")) {
        env.file = resolveFile(t, "file");
        env.map = readImage(env.file);
        for (const glm::vec3& p : env.map.pixels()) {
            if (p.x < 0.0f || p.y < 0.0f || p.z < 0.0f) {
                t.fail("file", "environment map has negative radiance");
            }
        }
    } else {
        env.radiance = floatVec3(t, "radiance");
        requireNonNegative(t, "radiance", env.radiance);
    }
    env.scale = static_cast<float>(requireFloat(t, "scale", t.number("scale", 1.0)));
    if (!(env.scale >= 0.0f)) {
        t.fail("scale", "value " + formatNumber(env.scale) + " is negative");
    }
    float brightest = std::max({env.radiance.x, env.radiance.y, env.radiance.z});
    for (const glm::vec3& p : env.map.pixels()) brightest = std::max({brightest, p.x, p.y, p.z});
    requireFloatProduct(t, "scale", brightest, env.scale, "the brightest environment radiance times scale");
    env.rotationDegrees = static_cast<float>(t.number("rotation", 0.0));
    t.finish();
}

// Nothing to render would give a silent white (or black) image in every mode: refuse it here.
void requireTriangles(const Scene& scene) {
    if (scene.triangleCount() == 0) {
        throw Error(scene.path + ": the scene has no triangles (none in its meshes, or all dropped as "
                                 "degenerate or duplicate)");
    }
}

Scene loadTomlScene(const std::string& path) {
    TomlDocument doc(path);
    StrictTable root = doc.root();
    Scene scene;
    scene.path = path;

    std::map<std::string, std::uint32_t> materialOf;
    for (StrictTable& t : root.tables("material")) {
        Material m = readMaterial(t, scene.textures);
        if (!materialOf.emplace(m.name, static_cast<std::uint32_t>(scene.materials.size())).second) {
            t.fail("name", "duplicate material name '" + m.name + "'");
        }
        scene.materials.push_back(m);
    }
    for (StrictTable& t : root.tables("mesh")) {
        readMesh(t, scene, materialOf);
    }
    for (StrictTable& t : root.tables("light")) {
        scene.lights.push_back(readLight(t));
    }
    if (auto env = root.table("environment")) {
        readEnvironment(*env, scene.environment);
    }
    if (auto cam = root.table("camera")) {
        readCamera(*cam, scene.camera);
    } else {
        scene.camera = fitCamera(scene.bounds(), {kDefaultResolution, kDefaultResolution});
    }
    root.finish();
    requireTriangles(scene);
    return scene;
}

// Something must light a file that brings no emitter at all (a bare mesh; a glTF model without
// KHR_lights_punctual or emissive materials, as most are): a headlight giving unit irradiance at
// the centre, and a white sky for the modes that use environment light. Said in the log.
void lightIfUnlit(Scene& scene, const std::string& path) {
    if (!scene.lights.empty() || scene.features().emissiveMeshes != 0 || scene.environment.present) return;
    const Bounds b = scene.bounds();
    Light head;
    head.position = scene.camera.pose.position;
    // Unit irradiance at the centre; a camera at the centre gets the bounding radius's worth.
    const float d = std::max(glm::length(scene.camera.pose.position - b.center()), b.radius());
    head.intensity = glm::vec3(d * d);
    scene.lights.push_back(head);
    scene.environment.present = true;
    scene.environment.radiance = glm::vec3(1.0f);
    log::info(path + ": no emitters; added a headlight and a constant white environment");
}

Scene loadBareMesh(const std::string& path) {
    Scene scene;
    scene.path = path;
    addMeshFile(scene, loadMeshFile(path), path, std::nullopt, {}, std::nullopt, glm::mat4(1.0f), {}, {});
    requireTriangles(scene);
    Bounds b = scene.bounds();
    scene.camera = fitCamera(b, {kDefaultResolution, kDefaultResolution});
    lightIfUnlit(scene, path);
    return scene;
}

// Scene::inputFiles: what the loader listed (every file it opened or looked for: includes,
// buffers, mesh files, MTLs and their textures, found or not) and every file the scene's parts
// name. A mesh a loader made itself (a tessellated shape) or an embedded image names no file of
// its own: of those names only existing files count.
void listInputFiles(Scene& scene, const std::string& path) {
    std::set<std::string> files(scene.inputFiles.begin(), scene.inputFiles.end());
    files.insert(path);
    const auto add = [&](const std::string& f) {
        std::error_code ec;
        if (!f.empty() && fs::is_regular_file(f, ec)) files.insert(f);
    };
    for (const Mesh& m : scene.meshes) add(m.sourceFile);
    for (const Texture& t : scene.textures) add(t.path);
    add(scene.environment.file);
    scene.inputFiles.assign(files.begin(), files.end());
}

} // namespace

Scene loadScene(const std::string& path) {
    if (!fs::is_regular_file(path)) {
        throw Error(path + ": file not found");
    }
    std::string ext = fs::path(path).extension().string();
    std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return std::tolower(c); });
    Scene scene = ext == ".toml"                     ? loadTomlScene(path)
                  : ext == ".xml"                    ? loadMitsubaScene(path)
                  : ext == ".gltf" || ext == ".glb" ? loadGltfScene(path)
                                                     : loadBareMesh(path);
    if (ext == ".gltf" || ext == ".glb") lightIfUnlit(scene, path);
    listInputFiles(scene, path);
    requireRepresentable(scene);
    if (recentreFarScene(scene)) {
        log::info(path + ": far from the origin; renderers work relative to its centre " + formatNumber(scene.origin.x) +
                  ", " + formatNumber(scene.origin.y) + ", " + formatNumber(scene.origin.z));
    }
    const LoadStats& s = scene.loadStats;
    if (s.degenerateTriangles || s.duplicateTriangles || s.repairedNormals) {
        log::info(path + ": dropped " + std::to_string(s.degenerateTriangles) + " degenerate and " +
                  std::to_string(s.duplicateTriangles) + " duplicate triangles, repaired " +
                  std::to_string(s.repairedNormals) + " normals");
    }
    return scene;
}

} // namespace bl
