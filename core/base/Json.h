// A minimal streaming JSON writer for result files (no JSON library is among our dependencies).
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

namespace bl {

class JsonWriter {
public:
    explicit JsonWriter(std::ostream& out) : mOut(out) {}

    JsonWriter& beginObject();
    JsonWriter& endObject();
    JsonWriter& beginArray();
    JsonWriter& endArray();
    JsonWriter& key(std::string_view k);
    JsonWriter& value(std::string_view v);
    JsonWriter& value(const char* v) { return value(std::string_view(v)); }
    JsonWriter& value(double v); // non-finite values are written as null
    JsonWriter& value(long long v);
    JsonWriter& value(unsigned long long v);
    JsonWriter& value(int v) { return value(static_cast<long long>(v)); }
    JsonWriter& value(unsigned v) { return value(static_cast<unsigned long long>(v)); }
    JsonWriter& value(unsigned long v) { return value(static_cast<unsigned long long>(v)); }
    JsonWriter& value(bool v);
    template <typename T> JsonWriter& field(std::string_view k, const T& v) { return key(k).value(v); }

    static std::string escape(std::string_view s);

private:
    void separate();
    JsonWriter& close(char bracket);
    std::ostream& mOut;
    std::vector<bool> mFirst; // per open container: no element written yet
    bool mAfterKey = false;
};

} // namespace bl
