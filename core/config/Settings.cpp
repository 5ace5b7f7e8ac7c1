#include "config/Settings.h"

#include "base/Error.h"

#include <charconv>
#include <cmath>

namespace bl {

std::string formatValue(const ParamValue& v) {
    if (auto b = std::get_if<bool>(&v)) return *b ? "true" : "false";
    if (auto i = std::get_if<std::int64_t>(&v)) return std::to_string(*i);
    if (auto d = std::get_if<double>(&v)) return formatNumber(*d);
    return std::get<std::string>(v);
}

const char* typeName(const ParamValue& v) {
    switch (v.index()) {
    case 0: return "bool";
    case 1: return "integer";
    case 2: return "number";
    default: return "string";
    }
}

Settings::Settings(std::vector<ParamSpec> specs) : mSpecs(std::move(specs)) {
    for (const ParamSpec& s : mSpecs) {
        mValues.push_back(s.defaultValue);
    }
}

std::size_t Settings::indexOf(const std::string& key) const {
    for (std::size_t i = 0; i < mSpecs.size(); ++i) {
        if (mSpecs[i].key == key) {
            return i;
        }
    }
    std::string known;
    for (const ParamSpec& s : mSpecs) {
        known += (known.empty() ? "" : ", ") + s.key;
    }
    throw Error("unknown parameter '" + key + "' (known: " + (known.empty() ? "none" : known) + ")");
}

void Settings::set(const std::string& key, const ParamValue& value) {
    std::size_t i = indexOf(key);
    const ParamSpec& spec = mSpecs[i];
    ParamValue v = value;
    // Integers are acceptable where numbers are expected.
    if (std::holds_alternative<double>(spec.defaultValue) && std::holds_alternative<std::int64_t>(v)) {
        v = static_cast<double>(std::get<std::int64_t>(v));
    }
    if (v.index() != spec.defaultValue.index()) {
        throw Error("parameter '" + key + "' expects a value of type " + typeName(spec.defaultValue) + ", got " +
                    typeName(v) + " '" + formatValue(v) + "'");
    }
    if (v.index() == 1 || v.index() == 2) {
        double x = v.index() == 1 ? static_cast<double>(std::get<std::int64_t>(v)) : std::get<double>(v);
        if (!std::isfinite(x) || x < spec.min || x > spec.max) {
            throw Error("parameter '" + key + "' = " + formatValue(v) + " outside [" + formatNumber(spec.min) +
                        ", " + formatNumber(spec.max) + "]");
        }
    }
    if (auto s = std::get_if<std::string>(&v); s && !spec.choices.empty()) {
        bool ok = false;
        std::string list;
        for (const std::string& c : spec.choices) {
            ok |= c == *s;
            list += (list.empty() ? "" : ", ") + c;
        }
        if (!ok) {
            throw Error("parameter '" + key + "' = '" + *s + "' is not one of " + list);
        }
    }
    mValues[i] = v;
}

void Settings::set(const std::string& key, const std::string& text) {
    const ParamValue& def = mSpecs[indexOf(key)].defaultValue;
    auto bad = [&]() -> Error {
        return Error("parameter '" + key + "' expects a value of type " + typeName(def) + ", got '" + text + "'");
    };
    switch (def.index()) {
    case 0:
        if (text == "true" || text == "1") return set(key, ParamValue(true));
        if (text == "false" || text == "0") return set(key, ParamValue(false));
        throw bad();
    case 1: {
        std::int64_t v = 0;
        auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || p != text.data() + text.size()) throw bad();
        return set(key, ParamValue(v));
    }
    case 2: {
        double v = 0;
        auto [p, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || p != text.data() + text.size()) throw bad();
        return set(key, ParamValue(v));
    }
    default:
        return set(key, ParamValue(text));
    }
}

void Settings::assign(const std::string& assignment) {
    auto eq = assignment.find('=');
    if (eq == std::string::npos || eq == 0) {
        throw Error("expected key=value, got '" + assignment + "'");
    }
    set(assignment.substr(0, eq), assignment.substr(eq + 1));
}

const ParamValue& Settings::value(const std::string& key) const { return mValues[indexOf(key)]; }
bool Settings::getBool(const std::string& key) const { return std::get<bool>(value(key)); }
std::int64_t Settings::getInt(const std::string& key) const { return std::get<std::int64_t>(value(key)); }
double Settings::getDouble(const std::string& key) const { return std::get<double>(value(key)); }
const std::string& Settings::getString(const std::string& key) const { return std::get<std::string>(value(key)); }

std::vector<std::pair<std::string, std::string>> Settings::resolved() const {
    std::vector<std::pair<std::string, std::string>> out;
    for (std::size_t i = 0; i < mSpecs.size(); ++i) {
        out.emplace_back(mSpecs[i].key, formatValue(mValues[i]));
    }
    return out;
}

} // namespace bl
