#include "config/StrictToml.h"

#include "base/Error.h"

#include <cmath>
#include <filesystem>
#include <toml++/toml.h>

namespace bl {

StrictTable::StrictTable(const toml::table& table, std::string file, std::string context)
    : mTable(&table), mFile(std::move(file)), mContext(std::move(context)) {}

int StrictTable::line() const { return static_cast<int>(mTable->source().begin.line); }

int StrictTable::line(const std::string& key) const {
    const toml::node* n = mTable->get(key);
    return n ? static_cast<int>(n->source().begin.line) : line();
}

bool StrictTable::has(const std::string& key) const { return mTable->contains(key); }

void StrictTable::fail(const std::string& key, const std::string& message) const {
    std::string what = mContext.empty() ? key : mContext + (key.empty() ? "" : "." + key);
    throwAt(mFile, line(key), what.empty() ? message : what + ": " + message);
}

const toml::node* StrictTable::find(const std::string& key) {
    mRead.insert(key);
    return mTable->get(key);
}

const toml::node& StrictTable::require(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) {
        throwAt(mFile, line(), (mContext.empty() ? "" : mContext + ": ") + "missing key '" + key + "'");
    }
    return *n;
}

namespace {
double finiteNumber(const StrictTable& t, const std::string& key, const toml::node& n) {
    std::optional<double> v = n.value<double>();
    if (!n.is_number() || !v) {
        t.fail(key, "expected a number");
    }
    if (!std::isfinite(*v)) {
        t.fail(key, "value " + formatNumber(*v) + " is not finite");
    }
    return *v;
}
} // namespace

double StrictTable::number(const std::string& key) { return finiteNumber(*this, key, require(key)); }

double StrictTable::number(const std::string& key, double fallback) {
    const toml::node* n = find(key);
    return n ? finiteNumber(*this, key, *n) : fallback;
}

std::int64_t StrictTable::integer(const std::string& key) {
    const toml::node& n = require(key);
    if (!n.is_integer()) {
        fail(key, "expected an integer");
    }
    return *n.value<std::int64_t>();
}

std::int64_t StrictTable::integer(const std::string& key, std::int64_t fallback) {
    return has(key) ? integer(key) : fallback;
}

std::string StrictTable::string(const std::string& key) {
    const toml::node& n = require(key);
    if (!n.is_string()) {
        fail(key, "expected a string");
    }
    return *n.value<std::string>();
}

std::string StrictTable::string(const std::string& key, const std::string& fallback) {
    return has(key) ? string(key) : fallback;
}

bool StrictTable::boolean(const std::string& key) {
    const toml::node& n = require(key);
    if (!n.is_boolean()) {
        fail(key, "expected true or false");
    }
    return *n.value<bool>();
}

bool StrictTable::boolean(const std::string& key, bool fallback) {
    return has(key) ? boolean(key) : fallback;
}

bool StrictTable::isArray(const std::string& key) const {
    const toml::node* n = mTable->get(key);
    return n && n->is_array();
}

std::vector<double> StrictTable::numbers(const std::string& key, std::size_t count) {
    const toml::node& n = require(key);
    const toml::array* a = n.as_array();
    if (!a || a->size() != count) {
        fail(key, "expected an array of " + std::to_string(count) + " numbers");
    }
    std::vector<double> out;
    for (const toml::node& e : *a) {
        out.push_back(finiteNumber(*this, key, e));
    }
    return out;
}

glm::vec3 StrictTable::vec3(const std::string& key) {
    std::vector<double> v = numbers(key, 3);
    return {v[0], v[1], v[2]};
}

glm::vec3 StrictTable::vec3(const std::string& key, const glm::vec3& fallback) {
    return has(key) ? vec3(key) : fallback;
}

glm::ivec2 StrictTable::ivec2(const std::string& key) {
    const toml::node& n = require(key);
    const toml::array* a = n.as_array();
    if (!a || a->size() != 2 || !(*a)[0].is_integer() || !(*a)[1].is_integer()) {
        fail(key, "expected an array of 2 integers");
    }
    return {static_cast<int>(*(*a)[0].value<std::int64_t>()),
            static_cast<int>(*(*a)[1].value<std::int64_t>())};
}

std::optional<StrictTable> StrictTable::table(const std::string& key) {
    const toml::node* n = find(key);
    if (!n) {
        return std::nullopt;
    }
    if (!n->is_table()) {
        fail(key, "expected a table");
    }
    return StrictTable(*n->as_table(), mFile, mContext.empty() ? key : mContext + "." + key);
}

std::vector<StrictTable> StrictTable::tables(const std::string& key) {
    std::vector<StrictTable> out;
    const toml::node* n = find(key);
    if (!n) {
        return out;
    }
    const toml::array* a = n->as_array();
    if (!a || !a->is_array_of_tables()) {
        fail(key, "expected an array of tables ([[" + key + "]])");
    }
    std::size_t i = 0;
    for (const toml::node& e : *a) {
        std::string name = (mContext.empty() ? "" : mContext + ".") + key + "[" + std::to_string(i++) + "]";
        out.emplace_back(*e.as_table(), mFile, name);
    }
    return out;
}

namespace {
ParamValue scalarValue(const StrictTable& t, const std::string& key, const toml::node& n) {
    if (n.is_boolean()) return ParamValue(*n.value<bool>());
    if (n.is_integer()) return ParamValue(*n.value<std::int64_t>());
    if (n.is_floating_point()) return ParamValue(finiteNumber(t, key, n));
    if (n.is_string()) return ParamValue(*n.value<std::string>());
    t.fail(key, "expected a boolean, number or string");
}
} // namespace

std::vector<StrictTable::Entry> StrictTable::entries(const std::string& key) {
    std::vector<Entry> out;
    const toml::node* n = find(key);
    if (!n) {
        return out;
    }
    const toml::table* t = n->as_table();
    if (!t) {
        fail(key, "expected a table");
    }
    StrictTable inner(*t, mFile, mContext.empty() ? key : mContext + "." + key);
    for (auto&& [k, v] : *t) {
        Entry e;
        e.key = std::string(k.str());
        e.line = static_cast<int>(v.source().begin.line);
        if (const toml::array* a = v.as_array()) {
            e.isArray = true;
            for (const toml::node& item : *a) {
                e.values.push_back(scalarValue(inner, e.key, item));
            }
            if (e.values.empty()) {
                inner.fail(e.key, "empty array");
            }
        } else {
            e.values.push_back(scalarValue(inner, e.key, v));
        }
        out.push_back(std::move(e));
    }
    return out;
}

std::vector<ParamValue> StrictTable::list(const std::string& key) {
    std::vector<ParamValue> out;
    const toml::node* n = find(key);
    if (!n) {
        return out;
    }
    const toml::array* a = n->as_array();
    if (!a) {
        fail(key, "expected an array");
    }
    for (const toml::node& item : *a) {
        out.push_back(scalarValue(*this, key, item));
    }
    return out;
}

void StrictTable::finish() const {
    for (auto&& [k, v] : *mTable) {
        std::string key(k.str());
        if (!mRead.count(key)) {
            throwAt(mFile, static_cast<int>(k.source().begin.line),
                    (mContext.empty() ? "" : mContext + ": ") + "unknown key '" + key + "'");
        }
    }
}

TomlDocument::TomlDocument(const std::string& path) : mPath(path) {
    if (!std::filesystem::is_regular_file(path)) {
        throw Error(path + ": file not found");
    }
    try {
        mTable = std::make_unique<toml::table>(toml::parse_file(path));
    } catch (const toml::parse_error& e) {
        throw Error(path + ":" + std::to_string(e.source().begin.line) + ":" +
                    std::to_string(e.source().begin.column) + ": TOML syntax error: " +
                    std::string(e.description()));
    }
}

TomlDocument::~TomlDocument() = default;
TomlDocument::TomlDocument(TomlDocument&&) noexcept = default;
TomlDocument& TomlDocument::operator=(TomlDocument&&) noexcept = default;

StrictTable TomlDocument::root() const { return StrictTable(*mTable, mPath, ""); }

} // namespace bl
