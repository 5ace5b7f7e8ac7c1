#include "base/Json.h"

#include "base/Error.h"

#include <cmath>
#include <cstdio>

namespace bl {

std::string JsonWriter::escape(std::string_view s) {
    std::string out = "\"";
    for (char c : s) {
        switch (c) {
        case '"': out += "\\\""; break;
        case '\\': out += "\\\\"; break;
        case '\n': out += "\\n"; break;
        case '\t': out += "\\t"; break;
        case '\r': out += "\\r"; break;
        default:
            if (static_cast<unsigned char>(c) < 0x20) {
                char buf[8];
                std::snprintf(buf, sizeof(buf), "\\u%04x", c);
                out += buf;
            } else {
                out += c;
            }
        }
    }
    return out + "\"";
}

void JsonWriter::separate() {
    if (mAfterKey) {
        mAfterKey = false;
        return;
    }
    if (!mFirst.empty()) {
        if (!mFirst.back()) {
            mOut << ",";
        }
        mFirst.back() = false;
        mOut << "\n" << std::string(2 * mFirst.size(), ' ');
    }
}

JsonWriter& JsonWriter::beginObject() {
    separate();
    mOut << "{";
    mFirst.push_back(true);
    return *this;
}

JsonWriter& JsonWriter::close(char bracket) {
    bool empty = mFirst.back();
    mFirst.pop_back();
    if (!empty) {
        mOut << "\n" << std::string(2 * mFirst.size(), ' ');
    }
    mOut << bracket;
    return *this;
}

JsonWriter& JsonWriter::endObject() { return close('}'); }

JsonWriter& JsonWriter::beginArray() {
    separate();
    mOut << "[";
    mFirst.push_back(true);
    return *this;
}

JsonWriter& JsonWriter::endArray() { return close(']'); }

JsonWriter& JsonWriter::key(std::string_view k) {
    separate();
    mOut << escape(k) << ": ";
    mAfterKey = true;
    return *this;
}

JsonWriter& JsonWriter::value(std::string_view v) {
    separate();
    mOut << escape(v);
    return *this;
}

JsonWriter& JsonWriter::value(double v) {
    separate();
    if (std::isfinite(v)) {
        mOut << formatNumber(v);
    } else {
        mOut << "null";
    }
    return *this;
}

JsonWriter& JsonWriter::value(long long v) {
    separate();
    mOut << v;
    return *this;
}

JsonWriter& JsonWriter::value(unsigned long long v) {
    separate();
    mOut << v;
    return *this;
}

JsonWriter& JsonWriter::value(bool v) {
    separate();
    mOut << (v ? "true" : "false");
    return *this;
}

} // namespace bl
