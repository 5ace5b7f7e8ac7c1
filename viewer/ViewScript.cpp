#include "viewer/ViewScript.h"

#include "base/Error.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace bl::viewer {

std::vector<ScriptCommand> loadViewScript(const std::string& path) {
    std::ifstream in(path);
    if (!in) throw Error(path + ": cannot read the view script");
    std::vector<ScriptCommand> out;
    std::string raw;
    for (int line = 1; std::getline(in, raw); ++line) {
        const std::string text = raw.substr(0, raw.find('#'));
        std::istringstream words(text);
        ScriptCommand c;
        c.line = line;
        if (!(words >> c.verb)) continue;
        const std::string where = path + ":" + std::to_string(line) + ": ";
        std::vector<std::string> args;
        for (std::string w; words >> w;) args.push_back(w);
        auto numbers = [&](std::size_t from, std::size_t to) {
            for (std::size_t i = from; i < to; ++i) {
                std::size_t used = 0;
                double v = 0.0;
                try {
                    v = std::stod(args[i], &used);
                } catch (const std::exception&) {
                    used = 0;
                }
                if (used != args[i].size() || !std::isfinite(v)) {
                    throw Error(where + c.verb + ": '" + args[i] + "' is not a finite number");
                }
                c.numbers.push_back(v);
            }
        };
        auto count = [&](std::size_t lo, std::size_t hi, const char* usage) {
            if (args.size() < lo || args.size() > hi) throw Error(where + "usage: " + usage);
        };
        if (c.verb == "pose") {
            if (args.size() != 6 && args.size() != 9) throw Error(where + "usage: pose PX PY PZ TX TY TZ [UX UY UZ]");
            numbers(0, args.size());
        } else if (c.verb == "key") {
            count(1, 1, "key NAME");
            c.text = args[0];
        } else if (c.verb == "drag") {
            count(2, 3, "drag DX DY [right]");
            numbers(0, 2);
            if (args.size() == 3) {
                if (args[2] != "right") throw Error(where + "drag: '" + args[2] + "' (expected `right` or nothing)");
                c.right = true;
            }
        } else if (c.verb == "scroll") {
            count(1, 1, "scroll STEPS");
            numbers(0, 1);
        } else if (c.verb == "set") {
            count(1, 1, "set KEY=VALUE");
            if (args[0].find('=') == std::string::npos) throw Error(where + "set: '" + args[0] + "' is not KEY=VALUE");
            c.text = args[0];
        } else if (c.verb == "iterate" || c.verb == "frames") {
            count(1, 1, (c.verb + " N").c_str());
            numbers(0, 1);
            if (!(c.numbers[0] >= 0.0 && c.numbers[0] <= 1e9 && c.numbers[0] == std::floor(c.numbers[0]))) {
                throw Error(where + c.verb + ": '" + args[0] + "' is not a count");
            }
        } else if (c.verb == "screenshot") {
            count(1, 1, "screenshot PATH.exr");
            c.text = args[0];
            if (c.text.size() < 4 || c.text.substr(c.text.size() - 4) != ".exr") {
                throw Error(where + "screenshot: '" + c.text + "' must end in .exr");
            }
        } else if (c.verb == "quit") {
            count(0, 0, "quit");
        } else {
            throw Error(where + "unknown command '" + c.verb +
                        "' (pose, key, drag, scroll, set, iterate, frames, screenshot, quit)");
        }
        out.push_back(c);
    }
    return out;
}

} // namespace bl::viewer
