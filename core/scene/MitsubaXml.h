// Reading Mitsuba 3 XML (pugixml): the main file and its <include>s flattened into the top-level
// elements in document order, <default> parameters substituted where attributes are read ($name),
// ids for <ref>, and the values a scene is written in (numbers, rgb, points, transforms composed
// in order, named properties checked against what an element supports). Every error names the
// file and line of the element. What the scene objects become: MitsubaLoader.cpp.
#pragma once

#include <glm/mat4x4.hpp>
#include <glm/vec3.hpp>
#include <pugixml.hpp>

#include <deque>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace bl::mitsuba {

// A parsed file, kept alive while its nodes are in use; its text gives line numbers.
struct Document {
    std::string path;
    std::string text;
    pugi::xml_document xml;
};

// An element and the document it came from.
struct Element {
    pugi::xml_node node;
    const Document* doc = nullptr;
};

class XmlReader {
public:
    // Reads `path` and every file it includes.
    explicit XmlReader(const std::string& path);

    // Top-level elements other than include and default, in document order.
    const std::vector<Element>& top() const { return mTop; }

    // "file:line: <tag type="...">: message" as a bl::Error.
    [[noreturn]] static void fail(const Element& e, const std::string& message);

    // An attribute with $name parameters replaced; required.
    std::string attribute(const Element& e, const char* name) const;
    // A file named in the scene: relative to the main file's folder (Mitsuba's file resolver),
    // else to the including file's.
    std::string resolve(const Element& e, const std::string& name) const;
    // The element a <ref id="..."/> names, which must be a `tag` (any element where empty).
    Element referenced(const Element& ref, const std::string& tag = "") const;

    std::vector<double> numbers(const Element& e, const std::string& text) const;
    double number(const Element& e, const char* name) const; // attribute `name`: one number
    int integer(const Element& e, const char* name) const;   // one whole number
    glm::dvec3 triple(const Element& e, const char* name) const;
    // x, y, z attributes (each defaulting to `fallback`) or one `value` of one or three numbers.
    glm::dvec3 components(const Element& e, double fallback) const;
    // An <rgb> or <float> value: non-negative, within float's range.
    glm::vec3 color(const Element& e) const;
    // The operations of a <transform>, each applied after the ones before.
    glm::dmat4 transform(const Element& e) const;

    // The named property children of an element (<float name="fov" .../> ...), checked against
    // what it supports; `ignored` ones are dropped and noted.
    std::map<std::string, Element> properties(const Element& e, const std::set<std::string>& supported,
                                              const std::set<std::string>& ignored = {});
    // A nested object or a reference (<bsdf name="..."> and <ref name="bsdf" .../> are allowed):
    // not a property, even with a name.
    static bool isObject(const pugi::xml_node& c);

    // How the file was read, one line per decision (Scene::importNotes).
    void note(const std::string& text);
    const std::vector<std::string>& notes() const { return mNotes; }
    // The main file and every file it includes, in the order read.
    std::vector<std::string> files() const;

private:
    void collect(const std::string& path, int depth, const Element* from);
    static std::size_t lineOf(const Document& doc, std::size_t offset);
    std::string substitute(const Element& e, std::string value) const;
    // An included file: relative to the including file's folder first (Mitsuba's parser), then
    // the main file's.
    std::string resolveInclude(const Element& e, const std::string& name) const;

    std::filesystem::path mRoot;
    std::deque<Document> mDocs;
    std::map<std::string, std::string> mDefaults;
    std::vector<Element> mTop;
    std::map<std::string, Element> mIds;
    std::vector<std::string> mNotes;
};

} // namespace bl::mitsuba
