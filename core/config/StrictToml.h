// Strict reading of TOML tables: every value is checked for type and finiteness, and a key that
// nobody read is an error naming the file, line and key (pbrt's ReportUnused). A typo never falls
// back to a default. Used for scene files and experiment configs alike.
#pragma once

#include "config/Settings.h"

#include <glm/glm.hpp>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

namespace toml {
inline namespace v3 {
class table;
class node;
} // namespace v3
} // namespace toml

namespace bl {

class StrictTable {
public:
    // `context` names the table in messages, e.g. "material 'white'" or "camera".
    StrictTable(const toml::table& table, std::string file, std::string context);

    const std::string& file() const { return mFile; }
    const std::string& context() const { return mContext; }
    int line() const;                       // line of the table itself
    int line(const std::string& key) const; // line of a key's value (the table's if absent)
    bool has(const std::string& key) const;

    // Required values: missing, wrong type or non-finite is an error.
    double number(const std::string& key);
    std::int64_t integer(const std::string& key);
    std::string string(const std::string& key);
    bool boolean(const std::string& key);
    glm::vec3 vec3(const std::string& key);
    glm::ivec2 ivec2(const std::string& key);
    // `count` finite numbers in double precision, before any narrowing to float.
    std::vector<double> numbers(const std::string& key, std::size_t count);

    // Optional values: absent gives the default; present but invalid is an error.
    double number(const std::string& key, double fallback);
    std::int64_t integer(const std::string& key, std::int64_t fallback);
    std::string string(const std::string& key, const std::string& fallback);
    bool boolean(const std::string& key, bool fallback);
    glm::vec3 vec3(const std::string& key, const glm::vec3& fallback);
    bool isArray(const std::string& key) const;

    std::optional<StrictTable> table(const std::string& key);

    // A free-form table's entries (e.g. mode settings, whose keys the mode knows, not the reader):
    // scalars as ParamValue, arrays as their elements. Non-finite numbers and nested tables are
    // errors. Marks the key read.
    struct Entry {
        std::string key;
        int line = 0;
        bool isArray = false;
        std::vector<ParamValue> values; // one for a scalar
    };
    std::vector<Entry> entries(const std::string& key);
    // An array of scalars (booleans, numbers, strings) as ParamValues; empty if absent.
    std::vector<ParamValue> list(const std::string& key);
    // An array of tables ([[key]]); empty if absent. Elements are named key[i] in messages.
    std::vector<StrictTable> tables(const std::string& key);

    // Throws for every key present but never read.
    void finish() const;

    [[noreturn]] void fail(const std::string& key, const std::string& message) const;

private:
    const toml::node* find(const std::string& key);
    const toml::node& require(const std::string& key);

    const toml::table* mTable;
    std::string mFile;
    std::string mContext;
    std::set<std::string> mRead;
};

// Parses a TOML file; a syntax error names the file, line and column. The returned document must
// outlive every StrictTable made from it.
class TomlDocument {
public:
    explicit TomlDocument(const std::string& path);
    ~TomlDocument();
    TomlDocument(TomlDocument&&) noexcept;
    TomlDocument& operator=(TomlDocument&&) noexcept;
    StrictTable root() const;
    const std::string& path() const { return mPath; }

private:
    std::string mPath;
    std::unique_ptr<toml::table> mTable;
};

} // namespace bl
