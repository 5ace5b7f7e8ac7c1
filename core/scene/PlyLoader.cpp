// Stanford PLY, ASCII and binary (either byte order): vertex x y z [nx ny nz] [u v | s t], and
// faces as a list property (polygons are fan-triangulated). Other properties are skipped.
#include "base/Error.h"
#include "scene/MeshFile.h"
#include "scene/TextParsing.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <memory>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace bl {
namespace {

enum class Format { Ascii, BinaryLittle, BinaryBig };

struct Property {
    std::string name;
    std::string type;      // scalar type, or the item type of a list
    std::string countType; // non-empty for list properties
};

struct Element {
    std::string name;
    std::size_t count = 0;
    std::vector<Property> properties;
};

std::size_t typeSize(const std::string& t) {
    if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
    if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
    if (t == "int" || t == "uint" || t == "float" || t == "int32" || t == "uint32" || t == "float32") return 4;
    if (t == "double" || t == "float64") return 8;
    return 0;
}

class BinaryReader {
public:
    BinaryReader(const std::string& path, const std::string& data, std::size_t pos, bool bigEndian)
        : mPath(path), mData(data), mPos(pos), mSwap(bigEndian != (std::endian::native == std::endian::big)) {}

    double read(const std::string& type) {
        std::size_t n = typeSize(type);
        if (mPos + n > mData.size()) {
            throw Error(mPath + ": binary PLY ends early (byte " + std::to_string(mPos) + ")");
        }
        unsigned char b[8];
        std::memcpy(b, mData.data() + mPos, n);
        mPos += n;
        if (mSwap) {
            std::reverse(b, b + n);
        }
        auto as = [&b]<typename T>(T) { T v; std::memcpy(&v, b, sizeof(T)); return static_cast<double>(v); };
        if (type == "char" || type == "int8") return as(std::int8_t{});
        if (type == "uchar" || type == "uint8") return as(std::uint8_t{});
        if (type == "short" || type == "int16") return as(std::int16_t{});
        if (type == "ushort" || type == "uint16") return as(std::uint16_t{});
        if (type == "int" || type == "int32") return as(std::int32_t{});
        if (type == "uint" || type == "uint32") return as(std::uint32_t{});
        if (type == "float" || type == "float32") return as(float{});
        return as(double{});
    }

private:
    const std::string& mPath;
    const std::string& mData;
    std::size_t mPos;
    bool mSwap;
};

} // namespace

MeshFile loadPly(const std::string& path) {
    const std::string data = readWholeFile(path);
    std::istringstream header(data);
    std::string line;
    int lineNo = 0;
    auto fail = [&](const std::string& m) { throwAt(path, lineNo, m); };
    std::getline(header, line);
    ++lineNo;
    if (line.rfind("ply", 0) != 0) {
        fail("not a PLY file (no 'ply' magic)");
    }
    Format format = Format::Ascii;
    std::vector<Element> elements;
    bool ended = false;
    while (std::getline(header, line)) {
        ++lineNo;
        if (!line.empty() && line.back() == '\r') {
            line.pop_back();
        }
        std::istringstream ls(line);
        std::string key;
        ls >> key;
        if (key == "format") {
            std::string f;
            ls >> f;
            if (f == "ascii") format = Format::Ascii;
            else if (f == "binary_little_endian") format = Format::BinaryLittle;
            else if (f == "binary_big_endian") format = Format::BinaryBig;
            else fail("unknown PLY format '" + f + "'");
        } else if (key == "element") {
            Element e;
            long long count = -1;
            ls >> e.name >> count;
            if (count < 0) {
                fail("element '" + e.name + "' has no valid count");
            }
            e.count = static_cast<std::size_t>(count);
            // Every element takes at least one byte, so a larger count is a corrupt header, and
            // must not become a huge allocation.
            if (e.count > data.size()) {
                fail("element '" + e.name + "' count " + std::to_string(count) +
                     " exceeds what the file can hold");
            }
            elements.push_back(e);
        } else if (key == "property") {
            if (elements.empty()) {
                fail("property before any element");
            }
            Property p;
            std::string type;
            ls >> type;
            if (type == "list") {
                ls >> p.countType >> p.type >> p.name;
                if (!typeSize(p.countType) || !typeSize(p.type)) fail("unknown list type");
            } else {
                p.type = type;
                ls >> p.name;
                if (!typeSize(p.type)) fail("unknown property type '" + type + "'");
            }
            elements.back().properties.push_back(p);
        } else if (key == "end_header") {
            ended = true;
            break;
        }
    }
    if (!ended) {
        fail("header has no end_header");
    }
    std::size_t bodyStart = static_cast<std::size_t>(header.tellg());

    MeshFile out;
    Mesh mesh;
    mesh.name = std::filesystem::path(path).filename().string();
    mesh.sourceFile = path;
    bool hasNormals = false, hasUv = false;

    std::unique_ptr<TextLines> text;
    std::unique_ptr<BinaryReader> binary;
    if (format == Format::Ascii) {
        text = std::make_unique<TextLines>(path, data.substr(bodyStart), lineNo + 1);
    } else {
        binary = std::make_unique<BinaryReader>(path, data, bodyStart, format == Format::BinaryBig);
    }
    std::vector<std::string_view> tokens;
    std::size_t tokenPos = 0;
    auto nextValue = [&](const std::string& type) -> double {
        if (binary) {
            return binary->read(type);
        }
        while (tokenPos >= tokens.size()) {
            if (!text->next(tokens)) {
                throwAt(path, text->lineNumber(), "PLY body ends early");
            }
            tokenPos = 0;
        }
        std::string_view tok = tokens[tokenPos++];
        return type == "float" || type == "double" || type == "float32" || type == "float64"
                   ? text->toFloat(tok)
                   : static_cast<double>(text->toInteger(tok));
    };
    auto where = [&]() { return text ? text->lineNumber() : 0; };

    for (const Element& e : elements) {
        if (e.name == "vertex") {
            mesh.positions.resize(e.count);
            for (const Property& p : e.properties) {
                hasNormals |= p.name == "nx";
                hasUv |= p.name == "u" || p.name == "s" || p.name == "texture_u";
            }
            if (hasNormals) mesh.normals.resize(e.count);
            if (hasUv) mesh.uvs.resize(e.count);
            for (std::size_t i = 0; i < e.count; ++i) {
                for (const Property& p : e.properties) {
                    if (!p.countType.empty()) {
                        std::size_t n = static_cast<std::size_t>(nextValue(p.countType));
                        for (std::size_t k = 0; k < n; ++k) nextValue(p.type);
                        continue;
                    }
                    double v = nextValue(p.type);
                    if (!std::isfinite(v)) {
                        throwAt(path, where(), "vertex " + std::to_string(i) + " property '" + p.name +
                                                   "' is not finite");
                    }
                    float f = static_cast<float>(v);
                    const std::string& n = p.name;
                    if (n == "x") mesh.positions[i].x = f;
                    else if (n == "y") mesh.positions[i].y = f;
                    else if (n == "z") mesh.positions[i].z = f;
                    else if (n == "nx") mesh.normals[i].x = f;
                    else if (n == "ny") mesh.normals[i].y = f;
                    else if (n == "nz") mesh.normals[i].z = f;
                    else if (n == "u" || n == "s" || n == "texture_u") mesh.uvs[i].x = f;
                    else if (n == "v" || n == "t" || n == "texture_v") mesh.uvs[i].y = f;
                }
            }
        } else if (e.name == "face") {
            for (std::size_t i = 0; i < e.count; ++i) {
                for (const Property& p : e.properties) {
                    if (p.countType.empty()) {
                        nextValue(p.type);
                        continue;
                    }
                    std::size_t n = static_cast<std::size_t>(nextValue(p.countType));
                    std::vector<std::uint32_t> ids(n);
                    for (std::size_t k = 0; k < n; ++k) {
                        double id = nextValue(p.type);
                        if (id < 0 || id >= static_cast<double>(mesh.positions.size())) {
                            throwAt(path, where(), "face " + std::to_string(i) + " refers to vertex " +
                                                       formatNumber(id) + " of " +
                                                       std::to_string(mesh.positions.size()));
                        }
                        ids[k] = static_cast<std::uint32_t>(id);
                    }
                    if (p.name != "vertex_indices" && p.name != "vertex_index") {
                        continue;
                    }
                    for (std::size_t k = 1; k + 1 < n; ++k) {
                        mesh.triangles.emplace_back(ids[0], ids[k], ids[k + 1]);
                    }
                }
            }
        } else {
            for (std::size_t i = 0; i < e.count; ++i) {
                for (const Property& p : e.properties) {
                    std::size_t n = p.countType.empty() ? 1 : static_cast<std::size_t>(nextValue(p.countType));
                    for (std::size_t k = 0; k < n; ++k) nextValue(p.type);
                }
            }
        }
    }
    Material m;
    m.name = "default";
    out.materials.push_back(m);
    out.materialEmission.emplace_back(0.0f);
    out.meshes.push_back(std::move(mesh));
    return out;
}

} // namespace bl
