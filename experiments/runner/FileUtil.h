// Small file helpers for results directories: every file is written to a temporary name and
// renamed, so a run killed at any moment leaves either the old file or the new one, never half.
#pragma once

#include <string>

namespace bl {

void writeFileAtomic(const std::string& path, const std::string& content);
bool readFileIfExists(const std::string& path, std::string& content);
// A CSV field, quoted when it needs to be.
std::string csvField(const std::string& value);

} // namespace bl
