// Minimal logging to stderr. Results go to files and stdout; diagnostics go here.
#pragma once

#include <string_view>

namespace bl::log {

enum class Level { Debug, Info, Warning, Error };

void setLevel(Level level);
Level level();

void write(Level level, std::string_view message);
inline void debug(std::string_view m) { write(Level::Debug, m); }
inline void info(std::string_view m) { write(Level::Info, m); }
inline void warn(std::string_view m) { write(Level::Warning, m); }
inline void error(std::string_view m) { write(Level::Error, m); }

} // namespace bl::log
