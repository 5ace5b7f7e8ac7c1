// Typed, documented parameters of a mode (or any configurable part). Each parameter has a key, a
// default, a unit, a range and a sentence; values are set from text (`--set key=value`, configs)
// with strict checking and read back with the same keys, so settings round-trip.
#pragma once

#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

namespace bl {

using ParamValue = std::variant<bool, std::int64_t, double, std::string>;

struct ParamSpec {
    std::string key;
    ParamValue defaultValue;
    std::string unit; // "" for dimensionless
    std::string help;
    double min = -std::numeric_limits<double>::infinity(); // numbers only
    double max = std::numeric_limits<double>::infinity();
    std::vector<std::string> choices; // strings only; empty = any
};

std::string formatValue(const ParamValue& v);
const char* typeName(const ParamValue& v);

class Settings {
public:
    Settings() = default;
    explicit Settings(std::vector<ParamSpec> specs);

    // Parses `text` by the parameter's type and checks its range; an unknown key lists the known ones.
    void set(const std::string& key, const std::string& text);
    void set(const std::string& key, const ParamValue& value);
    // "key=value"
    void assign(const std::string& assignment);

    bool getBool(const std::string& key) const;
    std::int64_t getInt(const std::string& key) const;
    double getDouble(const std::string& key) const;
    const std::string& getString(const std::string& key) const;

    const std::vector<ParamSpec>& specs() const { return mSpecs; }
    const ParamValue& value(const std::string& key) const;
    // Resolved (key, value as text) pairs, in declaration order.
    std::vector<std::pair<std::string, std::string>> resolved() const;

private:
    std::size_t indexOf(const std::string& key) const;
    std::vector<ParamSpec> mSpecs;
    std::vector<ParamValue> mValues;
};

} // namespace bl
