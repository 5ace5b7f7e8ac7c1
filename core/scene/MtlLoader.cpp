#include "scene/MtlLoader.h"

#include "base/Error.h"
#include "base/Log.h"
#include "image/ImageIO.h"
#include "scene/TextParsing.h"

#include <algorithm>
#include <filesystem>

namespace fs = std::filesystem;

namespace bl {

namespace {
std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
    return s;
}

glm::vec3 readColour(TextLines& in, const std::vector<std::string_view>& t) {
    if (t.size() < 2) {
        in.fail(std::string(t[0]) + " needs a value");
    }
    float r = in.toFloat(t[1]);
    // A single value means grey, as the MTL specification allows.
    return t.size() >= 4 ? glm::vec3(r, in.toFloat(t[2]), in.toFloat(t[3])) : glm::vec3(r);
}

void requireUnitRange(TextLines& in, std::string_view key, glm::vec3 c) {
    for (int i = 0; i < 3; ++i) {
        if (c[i] < 0.0f || c[i] > 1.0f) {
            in.fail(std::string(key) + " value " + formatNumber(c[i]) + " outside [0, 1]");
        }
    }
}
} // namespace

std::string resolveAssetPath(const std::string& dir, const std::string& name) {
    std::string cleaned = name;
    std::replace(cleaned.begin(), cleaned.end(), '\\', '/');
    fs::path direct = fs::path(dir) / cleaned;
    if (fs::is_regular_file(direct)) {
        return direct.string();
    }
    // Case-insensitive match, component by component.
    fs::path current = dir.empty() ? fs::path(".") : fs::path(dir);
    for (const fs::path& part : fs::path(cleaned)) {
        std::error_code ec;
        fs::path found;
        for (const auto& entry : fs::directory_iterator(current, ec)) {
            if (lower(entry.path().filename().string()) == lower(part.string())) {
                found = entry.path();
                break;
            }
        }
        if (found.empty()) {
            return "";
        }
        current = found;
    }
    return fs::is_regular_file(current) ? current.string() : "";
}

void MtlLibrary::load(const std::string& mtlPath, const std::string& objPath, int objLine) {
    if (!fs::is_regular_file(mtlPath)) {
        std::string resolved = resolveAssetPath(fs::path(mtlPath).parent_path().string(),
                                                fs::path(mtlPath).filename().string());
        if (resolved.empty()) {
            log::warn(objPath + ":" + std::to_string(objLine) + ": material library '" + mtlPath +
                      "' not found; its materials fall back to grey");
            mFiles.push_back(mtlPath);
            return;
        }
        return load(resolved, objPath, objLine);
    }
    mFiles.push_back(mtlPath);
    TextLines in(mtlPath);
    const std::string dir = fs::path(mtlPath).parent_path().string();
    Definition* current = nullptr;
    std::vector<std::string_view> t;
    while (in.next(t)) {
        if (t.empty()) {
            continue;
        }
        const std::string_view key = t[0];
        if (key == "newmtl") {
            if (t.size() < 2) {
                in.fail("newmtl needs a name");
            }
            std::string name(t[1]);
            current = &mDefinitions[name];
            current->material.name = name;
            continue;
        }
        if (!current) {
            if (key == "Kd" || key == "Ks" || key == "Ns" || key == "Ke" || key == "map_Kd") {
                in.fail(std::string(key) + " before any newmtl");
            }
            continue;
        }
        if (key == "Kd") {
            current->material.albedo = readColour(in, t);
            requireUnitRange(in, key, current->material.albedo);
        } else if (key == "Ks") {
            current->material.specular = readColour(in, t);
            requireUnitRange(in, key, current->material.specular);
        } else if (key == "Ns") {
            float n = readColour(in, t).x;
            if (n < 0.0f) {
                in.fail("Ns value " + formatNumber(n) + " is negative");
            }
            current->material.exponentU = current->material.exponentV = n;
        } else if (key == "Ke") {
            current->emission = readColour(in, t);
            if (glm::any(glm::lessThan(current->emission, glm::vec3(0.0f)))) {
                in.fail("Ke must not be negative");
            }
        } else if (key == "map_Kd") {
            // Options (-bm, -s, …) precede the file name, which is the last token.
            std::string file(t.back());
            current->texturePath = resolveAssetPath(dir, file);
            mFiles.push_back(current->texturePath.empty() ? (fs::path(dir) / file).string() : current->texturePath);
            if (current->texturePath.empty()) {
                log::warn(mtlPath + ":" + std::to_string(in.lineNumber()) + ": texture '" + file +
                          "' not found; material '" + current->material.name + "' uses its flat Kd");
            }
        }
    }
}

std::uint32_t MtlLibrary::indexOf(const std::string& name, MeshFile& out, const std::string& objPath,
                                  int objLine) {
    if (auto it = mUsed.find(name); it != mUsed.end()) {
        return it->second;
    }
    Definition def;
    if (auto it = mDefinitions.find(name); it != mDefinitions.end()) {
        def = it->second;
    } else {
        if (!name.empty()) {
            log::warn(objPath + ":" + std::to_string(objLine) + ": material '" + name +
                      "' is not defined in any MTL; using grey");
        }
        def.material.name = name.empty() ? "default" : name;
    }
    if (!def.texturePath.empty()) {
        auto [it, inserted] = mTextureOf.try_emplace(def.texturePath, static_cast<int>(out.textures.size()));
        if (inserted) {
            try {
                out.textures.push_back({def.texturePath, readRgba8(def.texturePath)});
            } catch (const Error& e) {
                log::warn(std::string(e.what()) + "; material '" + name + "' uses its flat Kd");
                mTextureOf.erase(it);
                it = mTextureOf.end();
            }
        }
        def.material.albedoTexture = it == mTextureOf.end() ? -1 : it->second;
    }
    std::uint32_t index = static_cast<std::uint32_t>(out.materials.size());
    out.materials.push_back(def.material);
    out.materialEmission.push_back(def.emission);
    mUsed[name] = index;
    return index;
}

} // namespace bl
