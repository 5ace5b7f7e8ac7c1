#include "scene/MitsubaLoader.h"

#include "base/Error.h"
#include "image/ImageIO.h"
#include "scene/MeshCleanup.h"
#include "scene/MeshFile.h"
#include "scene/MeshTransform.h"
#include "scene/MitsubaXml.h"
#include "scene/ShapeMeshes.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <set>

namespace bl {


namespace {

constexpr double kPi = 3.14159265358979323846;
// Mitsuba's defaults: an hdrfilm of 768 x 576, a diffuse bsdf of reflectance 0.5.
constexpr int kFilmWidth = 768, kFilmHeight = 576;
constexpr float kDefaultReflectance = 0.5f;

using mitsuba::Element;
using mitsuba::XmlReader;

class Importer {
public:
    explicit Importer(const std::string& path) : mXml(path) { mScene.path = path; }

    Scene run(const std::string& path) {
        for (const Element& e : mXml.top()) topLevel(e);
        if (mScene.meshes.empty()) {
            throw Error(path + ": the scene has no shapes");
        }
        if (!mCameraSet) {
            throw Error(path + ": no <sensor type=\"perspective\">: bundlelab needs the camera from the file");
        }
        mScene.importNotes = mXml.notes();
        const std::vector<std::string> documents = mXml.files();
        mScene.inputFiles.insert(mScene.inputFiles.end(), documents.begin(), documents.end());
        return std::move(mScene);
    }

private:
    // Mitsuba refuses a rectangle or disk whose to_world shears it.
    static void requireUnsheared(const Element& e, const glm::dmat4& m) {
        const glm::dvec3 x(m[0]), y(m[1]);
        if (std::abs(glm::dot(x, y)) > 1e-6 * glm::length(x) * glm::length(y)) XmlReader::fail(e, "to_world shears this shape");
    }

    // A to_world that scales all axes alike (a rotation, uniform scale and translation).
    static void requireSimilarity(const Element& e, const glm::dmat4& m, const std::string& message) {
        const glm::dvec3 x(m[0]), y(m[1]), z(m[2]);
        const double l = glm::length(x), tolerance = 1e-6 * l * l;
        if (std::abs(glm::dot(x, y)) > tolerance || std::abs(glm::dot(y, z)) > tolerance ||
            std::abs(glm::dot(x, z)) > tolerance || std::abs(glm::length(y) - l) > 1e-6 * l ||
            std::abs(glm::length(z) - l) > 1e-6 * l) {
            XmlReader::fail(e, message);
        }
    }

    // --- Scene objects -------------------------------------------------------------------------

    void topLevel(const Element& e) {
        const std::string tag = e.node.name();
        if (tag == "shape") {
            const std::string type = e.node.attribute("type").value();
            if (type == "instance") {
                instance(e);
            } else if (type != "shapegroup") { // a shape group is drawn by its instances
                shape(e, glm::dmat4(1.0));
            }
        } else if (tag == "sensor") {
            sensor(e);
        } else if (tag == "emitter") {
            // Mitsuba adds every top-level object; an area emitter waits for the shape that refers to it.
            if (std::string(e.node.attribute("type").value()) != "area" || !e.node.attribute("id")) emitter(e);
        } else if (tag == "bsdf" || tag == "texture") {
            // Used where a shape or a bsdf refers to it.
        } else if (tag == "integrator" || tag == "sampler" || tag == "rfilter" || tag == "film") {
            mXml.note("<" + tag + " type=\"" + e.node.attribute("type").value() +
                 "\"> ignored: how to render is the mode's choice, not the scene's");
        } else {
            XmlReader::fail(e, "element not supported (supported at the top: shape, bsdf, emitter, sensor, include, default; "
                    "integrator, sampler ignored)");
        }
    }

    std::uint32_t material(const Element& bsdf) {
        const std::string key = bsdf.doc->path + "#" + std::to_string(bsdf.node.offset_debug());
        if (const auto it = mMaterialOf.find(key); it != mMaterialOf.end()) return it->second;
        Material m;
        m.name = bsdf.node.attribute("id") ? bsdf.node.attribute("id").value() : "bsdf" + std::to_string(mScene.materials.size());
        Element inner = bsdf;
        if (std::string(bsdf.node.attribute("type").value()) == "twosided") {
            std::vector<Element> nested;
            for (const pugi::xml_node& c : bsdf.node.children("bsdf")) nested.push_back({c, bsdf.doc});
            for (const pugi::xml_node& c : bsdf.node.children("ref")) nested.push_back(mXml.referenced({c, bsdf.doc}, "bsdf"));
            if (nested.size() != 1) XmlReader::fail(bsdf, "a twosided bsdf holds exactly one bsdf (two different sides are not supported)");
            inner = nested.front();
        } else if (std::string(bsdf.node.attribute("type").value()) == "diffuse") {
            mXml.note("bsdf 'diffuse' (one-sided in Mitsuba) read as bundlelab's Lambertian, which reflects on both sides");
        }
        const std::string type = inner.node.attribute("type").value();
        if (type == "roughplastic") {
            roughPlastic(inner, m);
            const auto index = static_cast<std::uint32_t>(mScene.materials.size());
            mScene.materials.push_back(m);
            mMaterialOf.emplace(key, index);
            return index;
        }
        if (type != "diffuse") {
            XmlReader::fail(inner, "bsdf type not supported (supported: diffuse, roughplastic, twosided around either); "
                        "smooth (delta) bsdfs and conductors are not mapped to bundlelab's Lambert + Phong");
        }
        auto props = mXml.properties(inner, {"reflectance"});
        for (const pugi::xml_node& c : inner.node.children("ref")) {
            const Element ref{c, inner.doc};
            if (std::string(c.attribute("name").value()) != "reflectance") XmlReader::fail(ref, "only the reflectance may be a reference here");
            props.emplace("reflectance", ref);
        }
        m.albedo = glm::vec3(kDefaultReflectance);
        if (props.count("reflectance")) {
            const Element& r = props.at("reflectance");
            const std::string tag = r.node.name();
            if (tag == "texture" || tag == "ref") {
                m.albedo = glm::vec3(1.0f); // the texture is the reflectance
                m.albedoTexture = texture(tag == "ref" ? mXml.referenced(r, "texture") : r);
            } else {
                m.albedo = mXml.color(r);
            }
        }
        for (int c = 0; c < 3; ++c) {
            if (!(m.albedo[c] >= 0.0f && m.albedo[c] <= 1.0f)) XmlReader::fail(inner, "reflectance outside [0, 1]");
        }
        const auto index = static_cast<std::uint32_t>(mScene.materials.size());
        mScene.materials.push_back(m);
        mMaterialOf.emplace(key, index);
        return index;
    }

    // Mitsuba's roughplastic (a rough dielectric coating over a diffuse base) as Lambert + Phong, its
    // Fresnel factors held at normal incidence:
    //   Phong lobe: reflectance specular_reflectance x F0, F0 = ((eta - 1) / (eta + 1))^2, eta =
    //     int_ior / ext_ior; exponent (2 / alpha^2 - 2) / 4 (Beckmann's alpha matches the half-vector
    //     exponent 2 / alpha^2 - 2; bundlelab's Phong lobe is about the mirror direction, at twice the
    //     angle: a quarter), at most 1e6;
    //   Lambert: diffuse_reflectance x (1 - F0)^2 / (eta^2 (1 - F_int)), Mitsuba's linear form (its
    //     `nonlinear = false` default) with the transmittances in and out at normal incidence and F_int
    //     the interface's internal reflectance averaged over the cosine-weighted hemisphere (smooth
    //     interface, total internal reflection included).
    // What this leaves out is stated in the notes: Fresnel's rise toward grazing angles (the coating
    // reflects more and transmits less there), and the GGX distribution's longer tails.
    void roughPlastic(const Element& e, Material& m) {
        const auto props = mXml.properties(e, {"diffuse_reflectance", "specular_reflectance", "int_ior", "ext_ior", "alpha",
                                               "distribution", "nonlinear", "sample_visible"});
        const auto number = [&](const char* name, double fallback) {
            return props.count(name) ? mXml.number(props.at(name), "value") : fallback;
        };
        const glm::dvec3 diffuse = props.count("diffuse_reflectance") ? glm::dvec3(mXml.color(props.at("diffuse_reflectance")))
                                                                      : glm::dvec3(0.5);
        const glm::dvec3 specular = props.count("specular_reflectance") ? glm::dvec3(mXml.color(props.at("specular_reflectance")))
                                                                        : glm::dvec3(1.0);
        const double eta = number("int_ior", 1.49) / number("ext_ior", 1.000277);
        const double alpha = number("alpha", 0.1);
        if (!(eta > 1.0 && std::isfinite(eta))) XmlReader::fail(e, "int_ior / ext_ior = " + formatNumber(eta) + " (a coating needs it above 1)");
        if (!(alpha > 0.0 && alpha <= 1.0)) XmlReader::fail(e, "alpha " + formatNumber(alpha) + " outside (0, 1]");
        if (props.count("nonlinear") && mXml.attribute(props.at("nonlinear"), "value") == "true") {
            XmlReader::fail(e, "nonlinear = true is not supported (Mitsuba's linear default is)");
        }
        const std::string distribution = props.count("distribution") ? mXml.attribute(props.at("distribution"), "value") : "beckmann";
        const double f0 = (eta - 1.0) * (eta - 1.0) / ((eta + 1.0) * (eta + 1.0));
        const double fInternal = internalReflectance(eta);
        const double exponent = std::min((2.0 / (alpha * alpha) - 2.0) / 4.0, 1e6);
        if (exponent < 1.0) XmlReader::fail(e, "alpha " + formatNumber(alpha) + " is wider than a Phong exponent of 1");
        m.albedo = glm::vec3(diffuse * ((1.0 - f0) * (1.0 - f0) / (eta * eta * (1.0 - fInternal))));
        m.specular = glm::vec3(specular * f0);
        m.exponentU = m.exponentV = float(exponent);
        for (int c = 0; c < 3; ++c) {
            if (!(m.albedo[c] + m.specular[c] <= 1.0f)) XmlReader::fail(e, "the mapped reflectances sum above 1");
        }
        char text[256];
        std::snprintf(text, sizeof(text),
                      "roughplastic '%s' (eta %.4g, alpha %.4g, %s): Lambert of diffuse_reflectance x %.4g + Phong lobe of "
                      "specular_reflectance x F0 = %.4g, exponent %.6g",
                      m.name.c_str(), eta, alpha, distribution.c_str(),
                      (1.0 - f0) * (1.0 - f0) / (eta * eta * (1.0 - fInternal)), f0, exponent);
        mXml.note(text);
        // The error, measured by experiments/mitsuba/roughplastic-mapping.py on veach_mis.xml (eta 2,
        // alpha 0.005-0.1): glossy albedo mapping / Mitsuba 1.00 at normal incidence, 0.85 at 30 deg,
        // 0.34 at 60 deg, 0.09 at 75 deg (Phong's albedo falls as cos theta_i, the coating's Fresnel
        // rises); diffuse base 1.06-1.08 at normal incidence, 1.36 at 75 deg; the lobe's half-energy
        // cone equal within 1.5 %.
        mXml.note("roughplastic: Fresnel held at normal incidence (the coating's reflection rises toward grazing angles in "
                  "Mitsuba, not here), the microfacet lobe as Phong about the mirror direction" +
                  std::string(distribution == "ggx" ? " (GGX's longer tails cut)" : "") +
                  "; measured for eta 2: glossy albedo x1.00 at normal incidence, x0.85 at 30 deg, x0.34 at 60 deg, "
                  "diffuse base x1.07 at normal incidence, x1.36 at 75 deg (experiments/mitsuba/roughplastic-mapping.md)");
    }

    // The average reflectance of a smooth dielectric interface for light from inside (relative index
    // 1 / eta), cosine-weighted over the hemisphere: 2 int_0^1 F(mu) mu dmu, total internal reflection
    // (F = 1) beyond the critical angle. Midpoint rule on 4096 steps in mu (F is smooth but for the
    // kink at the critical angle, which costs O(1 / steps)).
    static double internalReflectance(double eta) {
        constexpr int kSteps = 4096;
        double sum = 0.0;
        for (int i = 0; i < kSteps; ++i) {
            const double mu = (i + 0.5) / kSteps;                   // cosine inside
            const double sinT2 = eta * eta * (1.0 - mu * mu);        // Snell, out of the denser medium
            double f = 1.0;
            if (sinT2 < 1.0) {
                const double cosT = std::sqrt(1.0 - sinT2);
                const double rs = (eta * mu - cosT) / (eta * mu + cosT);
                const double rp = (mu - eta * cosT) / (mu + eta * cosT);
                f = 0.5 * (rs * rs + rp * rp);
            }
            sum += f * mu;
        }
        return 2.0 * sum / kSteps;
    }

    // A bitmap texture (8-bit, sRGB-encoded as Mitsuba reads one unless `raw`; bilinear, repeat),
    // index into the scene's textures; one per file.
    int texture(const Element& t) {
        if (std::string(t.node.attribute("type").value()) != "bitmap") XmlReader::fail(t, "texture type not supported (supported: bitmap)");
        const auto props = mXml.properties(t, {"filename", "filter_type", "wrap_mode", "raw"});
        if (!props.count("filename")) XmlReader::fail(t, "missing <string name=\"filename\">");
        const auto is = [&](const char* name, const char* value) {
            return !props.count(name) || mXml.attribute(props.at(name), "value") == value;
        };
        if (!is("filter_type", "bilinear") || !is("wrap_mode", "repeat") || !is("raw", "false")) {
            XmlReader::fail(t, "only bilinear, repeating, sRGB-decoded bitmaps are supported (filter_type, wrap_mode, raw)");
        }
        const std::string path = mXml.resolve(props.at("filename"), mXml.attribute(props.at("filename"), "value"));
        if (const auto it = mTextureOf.find(path); it != mTextureOf.end()) return it->second;
        const int index = static_cast<int>(mScene.textures.size());
        mScene.textures.push_back({path, readRgba8(path)});
        mTextureOf.emplace(path, index);
        return index;
    }

    std::uint32_t defaultMaterial() {
        if (!mDefaultMaterial) {
            Material m;
            m.name = "mitsuba-default";
            m.albedo = glm::vec3(kDefaultReflectance);
            mDefaultMaterial = static_cast<std::uint32_t>(mScene.materials.size());
            mScene.materials.push_back(m);
            mXml.note("shapes without a bsdf get Mitsuba's default: diffuse, reflectance 0.5");
        }
        return *mDefaultMaterial;
    }

    glm::vec3 areaRadiance(const Element& emitter) {
        if (std::string(emitter.node.attribute("type").value()) != "area") {
            XmlReader::fail(emitter, "a shape's emitter must be of type 'area'");
        }
        const auto props = mXml.properties(emitter, {"radiance"});
        return props.count("radiance") ? mXml.color(props.at("radiance")) : glm::vec3(1.0f);
    }

    // <shape type="instance"> of a <shape type="shapegroup">: each shape of the group placed by
    // the instance's to_world after its own (copied into the scene: bundlelab has no instancing).
    void instance(const Element& e) {
        const auto props = mXml.properties(e, {"to_world"});
        const glm::dmat4 toWorld = props.count("to_world") ? mXml.transform(props.at("to_world")) : glm::dmat4(1.0);
        std::vector<Element> groups;
        for (const pugi::xml_node& c : e.node.children("ref")) groups.push_back(mXml.referenced({c, e.doc}, "shape"));
        if (groups.size() != 1 || std::string(groups[0].node.attribute("type").value()) != "shapegroup") {
            XmlReader::fail(e, "an instance refers to exactly one shapegroup (<ref id=\"...\"/>)");
        }
        for (const pugi::xml_node& c : groups[0].node.children()) {
            if (c.type() != pugi::node_element) continue;
            const Element child{c, groups[0].doc};
            if (std::string(c.name()) != "shape") XmlReader::fail(child, "a shapegroup holds shapes only");
            const std::string type = c.attribute("type").value();
            if (type == "instance" || type == "shapegroup") XmlReader::fail(child, "nested shape groups are not supported");
            shape(child, toWorld);
        }
        mXml.note("shapegroup instances copied into the scene");
    }

    // A shape's meshes in the scene, placed by `outer` after the shape's own to_world.
    void shape(const Element& e, const glm::dmat4& outer) {
        const std::string type = e.node.attribute("type").value();
        std::set<std::string> supported{"to_world"};
        if (type == "obj" || type == "ply") supported.insert({"filename", "face_normals"});
        if (type == "sphere") supported.insert({"center", "radius"});
        const auto props = mXml.properties(e, supported);
        std::optional<std::uint32_t> materialIndex;
        std::optional<glm::vec3> emission;
        for (const pugi::xml_node& c : e.node.children()) {
            if (c.type() != pugi::node_element || (c.attribute("name") && !XmlReader::isObject(c))) continue;
            const Element child{c, e.doc};
            const std::string tag = c.name();
            const Element target = tag == "ref" ? mXml.referenced(child) : child;
            const std::string kind = target.node.name();
            if (kind == "bsdf") {
                if (materialIndex) XmlReader::fail(child, "a shape has one bsdf");
                materialIndex = material(target);
            } else if (kind == "emitter") {
                if (emission) XmlReader::fail(child, "a shape has one emitter");
                emission = areaRadiance(target);
            } else {
                XmlReader::fail(child, "not supported inside a shape (supported: bsdf, emitter, ref, transform, properties)");
            }
        }
        const glm::dmat4 toWorld = outer * (props.count("to_world") ? mXml.transform(props.at("to_world")) : glm::dmat4(1.0));
        std::vector<Mesh> meshes;
        bool faceNormals = false;
        if (type == "obj" || type == "ply") {
            if (!props.count("filename")) XmlReader::fail(e, "missing <string name=\"filename\">");
            const std::string file = mXml.resolve(props.at("filename"), mXml.attribute(props.at("filename"), "value"));
            mScene.inputFiles.push_back(file);
            MeshFile mf = type == "obj" ? loadObj(file, false) : loadPly(file); // Mitsuba ignores MTL files
            meshes = std::move(mf.meshes);
            if (type == "ply") {
                // Mitsuba reads a PLY's v as it is (image row 0 at v = 0), an OBJ's flipped;
                // bundlelab flips every v (the OBJ convention): undo it for PLY.
                for (Mesh& mesh : meshes) {
                    for (glm::vec2& uv : mesh.uvs) uv.y = 1.0f - uv.y;
                }
            }
            if (props.count("face_normals")) {
                std::string value = mXml.attribute(props.at("face_normals"), "value");
                std::transform(value.begin(), value.end(), value.begin(), [](unsigned char c) { return std::tolower(c); });
                faceNormals = value == "true";
            }
        } else if (type == "rectangle") {
            requireUnsheared(e, toWorld);
            meshes.push_back(quadMesh({-1, -1, 0}, {2, 0, 0}, {0, 2, 0}));
        } else if (type == "cube") {
            meshes.push_back(cubeMesh());
        } else if (type == "disk") {
            requireUnsheared(e, toWorld);
            meshes.push_back(diskMesh(kMitsubaSphereSegments));
            mXml.note("disk tessellated into " + std::to_string(kMitsubaSphereSegments) + " triangles");
        } else if (type == "sphere") {
            requireSimilarity(e, toWorld, "a sphere's to_world must scale uniformly (Mitsuba renders a sphere of radius |M x|)");
            const glm::dvec3 centre = props.count("center") ? mXml.components(props.at("center"), 0.0) : glm::dvec3(0.0);
            const double radius = props.count("radius") ? mXml.number(props.at("radius"), "value") : 1.0;
            if (!(radius > 0.0)) XmlReader::fail(e, "radius must be positive");
            meshes.push_back(sphereMesh(centre, radius, kMitsubaSphereSegments));
            mXml.note("sphere tessellated into " + std::to_string(kMitsubaSphereSegments) + " x " +
                 std::to_string(kMitsubaSphereSegments / 2) + " quads with smooth normals (its area is 0.3% short of the sphere's)");
        } else {
            XmlReader::fail(e, "shape type not supported (supported: obj, ply, rectangle, cube, disk, sphere, shapegroup, instance)");
        }
        const std::uint32_t materialUsed = materialIndex ? *materialIndex : defaultMaterial();
        if (mScene.materials[materialUsed].albedoTexture >= 0 && type != "obj" && type != "ply") {
            XmlReader::fail(e, "a textured bsdf on an analytic shape is not supported (its texture coordinates are not mapped); "
                    "textures on obj and ply shapes are");
        }
        const std::string name = e.node.attribute("id") ? e.node.attribute("id").value() : type + std::to_string(mScene.meshes.size());
        const bool mirrored = glm::determinant(glm::dmat3(toWorld)) < 0.0;
        for (Mesh& mesh : meshes) {
            // Normals: the file's; Mitsuba smooths a mesh without them (all edges, no crease
            // angle) unless face_normals asks for flat ones.
            NormalOptions normals;
            const bool hasNormals = !mesh.normals.empty() && !faceNormals;
            if (faceNormals) {
                normals.source = NormalSource::Flat;
            } else if (mesh.normals.empty()) {
                normals.source = NormalSource::Smooth;
                normals.creaseDegrees = 180.0f;
                mXml.note("a mesh without normals gets smooth ones across every edge, as in Mitsuba (area-weighted here)");
            }
            bakeTransform(mesh, glm::mat4(toWorld));
            if (mirrored && hasNormals) {
                // A mirroring to_world turns the winding but not the normals, and Mitsuba's front
                // (the emitting side) follows the normals: turn the winding back.
                for (glm::uvec3& t : mesh.triangles) std::swap(t.y, t.z);
            }
            const CleanupStats stats = cleanupMesh(mesh, normals);
            mScene.loadStats.degenerateTriangles += stats.degenerateTriangles;
            mScene.loadStats.duplicateTriangles += stats.duplicateTriangles;
            mScene.loadStats.repairedNormals += stats.repairedNormals;
            if (mesh.triangles.empty()) continue;
            if (mesh.name.empty()) mesh.name = name;
            mesh.material = materialUsed;
            mesh.emission = emission.value_or(glm::vec3(0.0f));
            mScene.meshes.push_back(std::move(mesh));
        }
    }

    void emitter(const Element& e) {
        const std::string type = e.node.attribute("type").value();
        if (type == "point") {
            const auto props = mXml.properties(e, {"position", "intensity", "to_world"});
            Light l;
            glm::dvec3 p(0.0);
            if (props.count("position") && props.count("to_world")) {
                XmlReader::fail(e, "give a point light's position or its to_world, not both (Mitsuba refuses both too)");
            }
            if (props.count("position")) p = mXml.components(props.at("position"), 0.0);
            if (props.count("to_world")) p = glm::dvec3(mXml.transform(props.at("to_world")) * glm::dvec4(p, 1.0));
            l.position = glm::vec3(p);
            l.intensity = props.count("intensity") ? mXml.color(props.at("intensity")) : glm::vec3(1.0f);
            mScene.lights.push_back(l);
        } else if (type == "spot") {
            mScene.lights.push_back(spot(e));
        } else if (type == "envmap") {
            environmentMap(e);
        } else if (type == "constant") {
            const auto props = mXml.properties(e, {"radiance"});
            if (mScene.environment.present) XmlReader::fail(e, "a second environment emitter");
            mScene.environment.present = true;
            mScene.environment.radiance = props.count("radiance") ? mXml.color(props.at("radiance")) : glm::vec3(1.0f);
        } else if (type == "area") {
            XmlReader::fail(e, "an area emitter belongs inside a shape (or has an id a shape refers to)");
        } else {
            XmlReader::fail(e, "emitter type not supported (supported: area, point, spot, constant, envmap)");
        }
    }

    // Mitsuba's spot: the local +z axis of to_world, full intensity within beam_width, falling
    // linearly in angle to 0 at cutoff_angle. Read as bundlelab's spot (pbrt-v4's smoothstep in
    // cosine from the cone's inner to its outer angle) with the same angles; the note gives what
    // that changes: the emitted power and the largest difference of the profiles.
    Light spot(const Element& e) {
        const auto props = mXml.properties(e, {"intensity", "cutoff_angle", "beam_width", "to_world"});
        const double cutoff = props.count("cutoff_angle") ? mXml.number(props.at("cutoff_angle"), "value") : 20.0;
        const double beam = props.count("beam_width") ? mXml.number(props.at("beam_width"), "value") : 0.75 * cutoff;
        if (!(cutoff > 0.0 && cutoff <= 90.0)) XmlReader::fail(e, "cutoff_angle outside (0, 90] degrees");
        if (!(beam >= 0.0 && beam <= cutoff)) XmlReader::fail(e, "beam_width outside [0, cutoff_angle]");
        const glm::dmat4 m = props.count("to_world") ? mXml.transform(props.at("to_world")) : glm::dmat4(1.0);
        Light l;
        l.type = Light::Type::Spot;
        l.position = glm::vec3(m * glm::dvec4(0, 0, 0, 1));
        const glm::dvec3 axis = glm::dvec3(m * glm::dvec4(0, 0, 1, 0));
        if (!(glm::length(axis) > 0.0)) XmlReader::fail(e, "to_world collapses the spot's axis");
        l.direction = glm::vec3(glm::normalize(axis));
        l.intensity = props.count("intensity") ? mXml.color(props.at("intensity")) : glm::vec3(1.0f);
        l.coneAngleDegrees = float(cutoff);
        l.falloffDegrees = float(cutoff - beam);
        // The two profiles over the edge, and the power each emits (2 pi int profile sin).
        const double toRad = kPi / 180.0, cosOuter = std::cos(cutoff * toRad), cosInner = std::cos(beam * toRad);
        double ours = 0.0, theirs = 0.0, worst = 0.0;
        constexpr int kSteps = 4096;
        for (int i = 0; i < kSteps; ++i) {
            const double theta = (i + 0.5) / kSteps * cutoff * toRad, c = std::cos(theta);
            const double mitsuba = theta <= beam * toRad ? 1.0 : (cutoff * toRad - theta) / ((cutoff - beam) * toRad);
            double x = cosInner > cosOuter ? (c - cosOuter) / (cosInner - cosOuter) : 1.0;
            x = std::clamp(x, 0.0, 1.0);
            const double bundlelab = c >= cosInner ? 1.0 : x * x * (3.0 - 2.0 * x);
            ours += bundlelab * std::sin(theta);
            theirs += mitsuba * std::sin(theta);
            worst = std::max(worst, std::abs(bundlelab - mitsuba));
        }
        char text[256];
        std::snprintf(text, sizeof(text),
                      "spot (cutoff %g, beam %g degrees): Mitsuba's edge, linear in angle, read as a smoothstep in "
                      "cosine: emitted power %+.2f %%, the profile off by at most %.3f",
                      cutoff, beam, 100.0 * (ours / theirs - 1.0), worst);
        mXml.note(text);
        return l;
    }

    // Mitsuba's envmap looks a local direction v up at u = atan2(v.x, -v.z) / 2 pi, v = acos(v.y) /
    // pi (envmap.cpp), v = to_world^-1 d; bundlelab's lat-long (CONVENTIONS.md, shared/EnvMap.h)
    // looks d up at u = atan2(m.z, m.x) / 2 pi + 1/2 of m = R_y(-rotation) d: the same texel for
    // every d when to_world is a rotation by alpha about +y and rotation = alpha - 90 degrees.
    void environmentMap(const Element& e) {
        if (mScene.environment.present) XmlReader::fail(e, "a second environment emitter");
        const auto props = mXml.properties(e, {"filename", "scale", "to_world"});
        if (!props.count("filename")) XmlReader::fail(e, "missing <string name=\"filename\">");
        Environment& env = mScene.environment;
        env.file = mXml.resolve(props.at("filename"), mXml.attribute(props.at("filename"), "value"));
        env.map = readImage(env.file);
        for (const glm::vec3& p : env.map.pixels()) {
            if (!(p.x >= 0.0f && p.y >= 0.0f && p.z >= 0.0f)) XmlReader::fail(e, "the map has negative or non-finite radiance");
        }
        env.scale = props.count("scale") ? float(mXml.number(props.at("scale"), "value")) : 1.0f;
        if (!(env.scale >= 0.0f)) XmlReader::fail(e, "negative scale");
        double alpha = 0.0;
        if (props.count("to_world")) {
            const glm::dmat4 m = mXml.transform(props.at("to_world"));
            const glm::dmat3 r(m);
            const double off = glm::length(glm::dvec3(r[1]) - glm::dvec3(0, 1, 0)) +
                               std::abs(r[0][1]) + std::abs(r[2][1]) + std::abs(glm::determinant(r) - 1.0) +
                               std::abs(glm::dot(r[0], r[0]) - 1.0) + std::abs(glm::dot(r[0], r[2]));
            if (off > 1e-6) XmlReader::fail(props.at("to_world"), "an envmap's to_world must be a rotation about +y");
            alpha = std::atan2(-r[0][2], r[0][0]) * 180.0 / kPi;
        }
        env.rotationDegrees = float(alpha - 90.0);
        env.present = true;
        mXml.note("envmap read with rotation " + formatNumber(env.rotationDegrees) +
             " degrees (Mitsuba's longitude starts at -z, bundlelab's at -x)");
    }

    void sensor(const Element& e) {
        if (mCameraSet) XmlReader::fail(e, "a second sensor (bundlelab renders one camera)");
        if (std::string(e.node.attribute("type").value()) != "perspective") {
            XmlReader::fail(e, "sensor type not supported (supported: perspective)");
        }
        const auto props = mXml.properties(e, {"fov", "fov_axis", "to_world"}, {"near_clip", "far_clip", "focus_distance"});
        int width = kFilmWidth, height = kFilmHeight;
        for (const pugi::xml_node& c : e.node.children()) {
            if (c.type() != pugi::node_element || c.attribute("name")) continue;
            const Element child{c, e.doc};
            const std::string tag = c.name();
            if (tag == "sampler") {
                mXml.note("<sampler> ignored: the samples are the mode's");
            } else if (tag == "film") {
                if (std::string(c.attribute("type").value()) != "hdrfilm") XmlReader::fail(child, "film type not supported (supported: hdrfilm)");
                const auto film = mXml.properties(child, {"width", "height"}, {"pixel_format", "rfilter", "component_format"});
                for (const pugi::xml_node& f : c.children("rfilter")) {
                    mXml.note(std::string("<rfilter type=\"") + f.attribute("type").value() + "\"> ignored: pixels are box-filtered");
                }
                if (film.count("width")) width = mXml.integer(film.at("width"), "value");
                if (film.count("height")) height = mXml.integer(film.at("height"), "value");
                if (width < 1 || height < 1 || width > 16384 || height > 16384) XmlReader::fail(child, "film size outside [1, 16384]");
            } else {
                XmlReader::fail(child, "not supported inside a sensor (supported: film, sampler)");
            }
        }
        if (!props.count("fov")) XmlReader::fail(e, "missing <float name=\"fov\"> (focal_length is not supported)");
        double fov = mXml.number(props.at("fov"), "value");
        if (!(fov > 0.0 && fov < 180.0)) XmlReader::fail(props.at("fov"), "fov outside (0, 180) degrees");
        const std::string axis = props.count("fov_axis") ? mXml.attribute(props.at("fov_axis"), "value") : "x";
        FovAxis fovAxis = FovAxis::X;
        if (axis == "y" || (axis == "smaller" && height < width) || (axis == "larger" && height > width)) {
            fovAxis = FovAxis::Y;
        } else if (axis == "diagonal") {
            // The same frustum with the angle across x.
            const double t = std::tan(0.5 * fov * kPi / 180.0) * width / std::hypot(double(width), double(height));
            fov = 2.0 * std::atan(t) * 180.0 / kPi;
            mXml.note("sensor fov_axis 'diagonal' converted to " + formatNumber(fov) + " degrees across x");
        } else if (axis != "x" && axis != "smaller" && axis != "larger") {
            XmlReader::fail(props.at("fov_axis"), "fov_axis '" + axis + "' not supported (x, y, smaller, larger, diagonal)");
        }
        const glm::dmat4 m = props.count("to_world") ? mXml.transform(props.at("to_world")) : glm::dmat4(1.0);
        const glm::dmat3 r(m);
        const glm::dmat3 product = r * glm::transpose(r);
        double off = 0.0;
        for (int i = 0; i < 3; ++i) {
            for (int j = 0; j < 3; ++j) off = std::max(off, std::abs(product[i][j] - (i == j ? 1.0 : 0.0)));
        }
        if (off > 1e-5) XmlReader::fail(props.at("to_world"), "a sensor's to_world may not scale (Mitsuba refuses it too)");
        if (glm::determinant(r) < 0.0) {
            XmlReader::fail(props.at("to_world"), "a mirrored sensor (to_world with a negative determinant) is not supported");
        }
        Camera& camera = mScene.camera;
        camera.pose.position = glm::vec3(m * glm::dvec4(0, 0, 0, 1));
        camera.pose.target = glm::vec3(m * glm::dvec4(0, 0, 1, 1));
        camera.pose.up = glm::vec3(glm::normalize(glm::dvec3(m * glm::dvec4(0, 1, 0, 0))));
        camera.fovDegrees = float(fov);
        camera.fovAxis = fovAxis;
        camera.resolution = {width, height};
        mCameraSet = true;
    }

    XmlReader mXml;
    std::map<std::string, std::uint32_t> mMaterialOf;
    std::map<std::string, int> mTextureOf;
    std::optional<std::uint32_t> mDefaultMaterial;
    bool mCameraSet = false;
    Scene mScene;
};

} // namespace

Scene loadMitsubaScene(const std::string& path) { return Importer(path).run(path); }

} // namespace bl
