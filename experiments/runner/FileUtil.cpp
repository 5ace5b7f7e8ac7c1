#include "runner/FileUtil.h"

#include "base/Error.h"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace fs = std::filesystem;

namespace bl {

void writeFileAtomic(const std::string& path, const std::string& content) {
    fs::path p(path);
    if (p.has_parent_path()) {
        fs::create_directories(p.parent_path());
    }
    // Host and process in the name: array elements on several nodes may share the directory.
    char host[256] = {};
    ::gethostname(host, sizeof(host) - 1);
    const std::string tmp = path + ".tmp-" + host + "-" + std::to_string(::getpid());
    {
        std::ofstream out(tmp, std::ios::binary);
        out << content;
        out.flush();
        if (!out) {
            throw Error(path + ": cannot write");
        }
    }
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) {
        fs::remove(tmp);
        throw Error(path + ": cannot write: " + ec.message());
    }
}

bool readFileIfExists(const std::string& path, std::string& content) {
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        return false;
    }
    std::ostringstream ss;
    ss << in.rdbuf();
    content = ss.str();
    return true;
}

std::string csvField(const std::string& value) {
    if (value.find_first_of(",\"\n") == std::string::npos) {
        return value;
    }
    std::string out = "\"";
    for (char c : value) {
        out += c == '"' ? std::string("\"\"") : std::string(1, c);
    }
    return out + "\"";
}

} // namespace bl
