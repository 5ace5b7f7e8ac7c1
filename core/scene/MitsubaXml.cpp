#include "scene/MitsubaXml.h"

#include "base/Error.h"

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

namespace bl::mitsuba {

namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;
// Includes nested deeper than this are a cycle.
constexpr int kMaxIncludeDepth = 16;

// Mitsuba's up for a lookat without one: the first vector of coordinate_system(n) (Duff et
// al.'s frame), (1, 0, 0) when looking down -z.
glm::dvec3 perpendicular(const glm::dvec3& n) {
    const double sign = std::copysign(1.0, n.z), a = -1.0 / (sign + n.z), b = n.x * n.y * a;
    return {n.x * n.x * a * sign + 1.0, b * sign, -n.x * sign};
}

} // namespace

XmlReader::XmlReader(const std::string& path) : mRoot(fs::path(path).parent_path()) { collect(path, 0, nullptr); }

std::vector<std::string> XmlReader::files() const {
    std::vector<std::string> out;
    for (const Document& d : mDocs) out.push_back(d.path);
    return out;
}

void XmlReader::collect(const std::string& path, int depth, const Element* from) {
    if (depth > kMaxIncludeDepth) {
        fail(*from, "includes nested deeper than " + std::to_string(kMaxIncludeDepth) + " (a cycle?)");
    }
    Document& doc = mDocs.emplace_back();
    doc.path = path;
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        if (from) fail(*from, "cannot open '" + path + "'");
        throw Error(path + ": file not found");
    }
    std::stringstream buffer;
    buffer << in.rdbuf();
    doc.text = buffer.str();
    const pugi::xml_parse_result parsed = doc.xml.load_buffer(doc.text.data(), doc.text.size());
    if (!parsed) {
        throw Error(path + ":" + std::to_string(lineOf(doc, std::size_t(parsed.offset))) + ": XML: " +
                    parsed.description());
    }
    const pugi::xml_node root = doc.xml.child("scene");
    if (!root) {
        throw Error(path + ": no <scene> element");
    }
    for (const pugi::xml_node& node : root.children()) {
        if (node.type() != pugi::node_element) continue;
        const Element e{node, &doc};
        const std::string tag = node.name();
        if (tag == "include") {
            collect(resolveInclude(e, attribute(e, "filename")), depth + 1, &e);
        } else if (tag == "default") {
            // The first definition wins (Mitsuba: a -D on the command line, then the file's).
            mDefaults.emplace(attribute(e, "name"), node.attribute("value").value());
        } else {
            mTop.push_back(e);
            if (node.attribute("id")) {
                const std::string id = node.attribute("id").value();
                if (!mIds.emplace(id, e).second) fail(e, "duplicate id '" + id + "'");
            }
        }
    }
}

std::size_t XmlReader::lineOf(const Document& doc, std::size_t offset) {
    offset = std::min(offset, doc.text.size());
    return 1 + std::size_t(std::count(doc.text.begin(), doc.text.begin() + std::ptrdiff_t(offset), '\n'));
}

void XmlReader::fail(const Element& e, const std::string& message) {
    throw Error(e.doc->path + ":" + std::to_string(lineOf(*e.doc, std::size_t(e.node.offset_debug()))) + ": <" +
                e.node.name() + (e.node.attribute("type") ? std::string(" type=\"") + e.node.attribute("type").value() + "\"" : "") +
                ">: " + message);
}

// An attribute with $name parameters replaced; required.
std::string XmlReader::attribute(const Element& e, const char* name) const {
    const pugi::xml_attribute a = e.node.attribute(name);
    if (!a) fail(e, std::string("missing attribute '") + name + "'");
    return substitute(e, a.value());
}

std::string XmlReader::substitute(const Element& e, std::string value) const {
    for (std::size_t at = value.find('$'); at != std::string::npos; at = value.find('$', at)) {
        std::size_t end = at + 1;
        while (end < value.size() && (std::isalnum(static_cast<unsigned char>(value[end])) || value[end] == '_')) ++end;
        const std::string name = value.substr(at + 1, end - at - 1);
        const auto it = mDefaults.find(name);
        if (it == mDefaults.end()) fail(e, "parameter '$" + name + "' has no <default>");
        value.replace(at, end - at, it->second);
        at += it->second.size();
    }
    return value;
}

// A file named in the scene: relative to the main file's folder (Mitsuba's file resolver),
// else to the including file's.
std::string XmlReader::resolve(const Element& e, const std::string& name) const {
    const fs::path p(name);
    if (p.is_absolute()) return name;
    if (fs::exists(mRoot / p)) return (mRoot / p).string();
    const fs::path local = fs::path(e.doc->path).parent_path() / p;
    if (fs::exists(local)) return local.string();
    fail(e, "file '" + name + "' not found (looked in " + mRoot.string() + " and " +
                fs::path(e.doc->path).parent_path().string() + ")");
}

// An included file: relative to the including file's folder first (Mitsuba's parser), then
// the main file's.
std::string XmlReader::resolveInclude(const Element& e, const std::string& name) const {
    const fs::path local = fs::path(e.doc->path).parent_path() / name;
    if (!fs::path(name).is_absolute() && fs::exists(local)) return local.string();
    return resolve(e, name);
}

Element XmlReader::referenced(const Element& ref, const std::string& tag) const {
    const std::string id = attribute(ref, "id");
    const auto it = mIds.find(id);
    if (it == mIds.end()) fail(ref, "no element with id '" + id + "'");
    if (!tag.empty() && tag != it->second.node.name()) {
        fail(ref, "id '" + id + "' is a <" + it->second.node.name() + ">, not a <" + tag + ">");
    }
    return it->second;
}

std::vector<double> XmlReader::numbers(const Element& e, const std::string& text) const {
    std::string s = text;
    std::replace(s.begin(), s.end(), ',', ' ');
    std::istringstream in(s);
    std::vector<double> out;
    std::string word;
    while (in >> word) {
        char* end = nullptr;
        const double v = std::strtod(word.c_str(), &end);
        if (end != word.c_str() + word.size() || !std::isfinite(v)) fail(e, "'" + text + "' is not a list of finite numbers");
        out.push_back(v);
    }
    return out;
}

double XmlReader::number(const Element& e, const char* name) const {
    const std::vector<double> v = numbers(e, attribute(e, name));
    if (v.size() != 1) fail(e, std::string("attribute '") + name + "' must be one number");
    return v[0];
}

glm::dvec3 XmlReader::triple(const Element& e, const char* name) const {
    const std::vector<double> v = numbers(e, attribute(e, name));
    if (v.size() != 3) fail(e, std::string("attribute '") + name + "' must be three numbers");
    return {v[0], v[1], v[2]};
}

// x, y, z attributes (each defaulting to `fallback`) or one `value` of three numbers.
glm::dvec3 XmlReader::components(const Element& e, double fallback) const {
    if (e.node.attribute("value")) {
        const std::vector<double> v = numbers(e, attribute(e, "value"));
        if (v.size() == 1) return glm::dvec3(v[0]);
        if (v.size() != 3) fail(e, "'value' must be one or three numbers");
        return {v[0], v[1], v[2]};
    }
    glm::dvec3 out(fallback);
    const char* axes[] = {"x", "y", "z"};
    for (int i = 0; i < 3; ++i) {
        if (e.node.attribute(axes[i])) out[i] = number(e, axes[i]);
    }
    return out;
}

// The named property children of an element (<float name="fov" .../> ...), checked against
// what this element supports.
std::map<std::string, Element> XmlReader::properties(const Element& e, const std::set<std::string>& supported,
                                          const std::set<std::string>& ignored) {
    std::map<std::string, Element> out;
    for (const pugi::xml_node& c : e.node.children()) {
        if (c.type() != pugi::node_element || !c.attribute("name") || isObject(c)) continue;
        const Element child{c, e.doc};
        const std::string name = c.attribute("name").value();
        if (ignored.count(name)) {
            note(std::string("<") + e.node.name() + "> '" + name + "' ignored");
            continue;
        }
        if (!supported.count(name)) {
            std::string list;
            for (const std::string& s : supported) list += (list.empty() ? "" : ", ") + s;
            fail(child, "property '" + name + "' is not supported here (supported: " + list + ")");
        }
        out.emplace(name, child);
    }
    return out;
}

// A nested object or a reference (<bsdf name="..."> and <ref name="bsdf" .../> are allowed):
// not a property, even with a name. A texture with a name is a property's value.
bool XmlReader::isObject(const pugi::xml_node& c) {
    const std::string tag = c.name();
    return tag == "ref" || tag == "bsdf" || tag == "emitter" || tag == "shape";
}

glm::vec3 XmlReader::color(const Element& e) const {
    const std::string tag = e.node.name();
    if (tag != "rgb" && tag != "float") {
        fail(e, "only <rgb> or <float> values are supported (no spectra or textures yet)");
    }
    const std::vector<double> v = numbers(e, attribute(e, "value"));
    if (!(v.size() == 1 || (v.size() == 3 && tag == "rgb"))) fail(e, "an <rgb> value has three numbers, a <float> one");
    for (double x : v) {
        // Every colour here (reflectance, radiance, intensity) is non-negative and rendered in float.
        if (x < 0.0) fail(e, "value " + formatNumber(x) + " is negative");
        if (x > double(std::numeric_limits<float>::max())) {
            fail(e, "value " + formatNumber(x) + " is more than a 32-bit float holds");
        }
    }
    if (v.size() == 1) return glm::vec3(float(v[0]));
    return {float(v[0]), float(v[1]), float(v[2])};
}

int XmlReader::integer(const Element& e, const char* name) const {
    const double v = number(e, name);
    if (v != std::floor(v) || std::abs(v) > double(std::numeric_limits<int>::max())) {
        fail(e, std::string("attribute '") + name + "' must be an integer, got " + formatNumber(v));
    }
    return int(v);
}

glm::dmat4 XmlReader::transform(const Element& e) const {
    glm::dmat4 m(1.0);
    for (const pugi::xml_node& c : e.node.children()) {
        if (c.type() != pugi::node_element) continue;
        const Element op{c, e.doc};
        const std::string tag = c.name();
        glm::dmat4 t(1.0);
        if (tag == "translate") {
            t = glm::translate(glm::dmat4(1.0), components(op, 0.0));
        } else if (tag == "scale") {
            t = glm::scale(glm::dmat4(1.0), components(op, 1.0));
        } else if (tag == "rotate") {
            const glm::dvec3 axis = components(op, 0.0);
            if (!(glm::length(axis) > 0.0)) fail(op, "rotation axis is zero");
            t = glm::rotate(glm::dmat4(1.0), number(op, "angle") * kPi / 180.0, glm::normalize(axis));
        } else if (tag == "matrix") {
            const std::vector<double> v = numbers(op, attribute(op, "value"));
            if (v.size() != 16 && v.size() != 9) fail(op, "a matrix has 16 (or 9) numbers, row by row");
            const int n = v.size() == 16 ? 4 : 3;
            for (int r = 0; r < n; ++r) {
                for (int col = 0; col < n; ++col) t[col][r] = v[std::size_t(r * n + col)];
            }
        } else if (tag == "lookat") {
            const glm::dvec3 origin = triple(op, "origin"), target = triple(op, "target");
            if (!(glm::length(target - origin) > 0.0)) fail(op, "'origin' and 'target' are the same point");
            const glm::dvec3 dir = glm::normalize(target - origin);
            const glm::dvec3 up = op.node.attribute("up") ? triple(op, "up") : perpendicular(dir);
            glm::dvec3 left = glm::cross(up, dir);
            if (!(glm::length(left) > 0.0)) fail(op, "'up' is parallel to the view direction");
            left = glm::normalize(left);
            const glm::dvec3 newUp = glm::cross(dir, left);
            t = glm::dmat4(glm::dvec4(left, 0.0), glm::dvec4(newUp, 0.0), glm::dvec4(dir, 0.0), glm::dvec4(origin, 1.0));
        } else {
            fail(op, "transform operation not supported (supported: translate, rotate, scale, matrix, lookat)");
        }
        m = t * m;
    }
    return m;
}

void XmlReader::note(const std::string& text) {
    if (std::find(mNotes.begin(), mNotes.end(), text) == mNotes.end()) mNotes.push_back(text);
}

} // namespace bl::mitsuba
