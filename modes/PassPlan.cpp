#include "modes/PassPlan.h"

#include "base/Error.h"

#include <algorithm>

namespace bl {

PassPlan& PassPlan::add(PlannedPass pass) {
    if (has(pass.id)) throw Error("pass plan: two passes with id '" + pass.id + "'");
    mPasses.push_back(std::move(pass));
    return *this;
}

PassPlan& PassPlan::add(std::string id, std::string name, bool runs, std::string code, std::string reason,
                        bool lightLeftOut) {
    return add(PlannedPass{std::move(id), std::move(name), runs, std::move(code), std::move(reason), lightLeftOut});
}

bool PassPlan::has(std::string_view id) const {
    return std::any_of(mPasses.begin(), mPasses.end(), [&](const PlannedPass& p) { return p.id == id; });
}

const PlannedPass& PassPlan::pass(std::string_view id) const {
    for (const PlannedPass& p : mPasses) {
        if (p.id == id) return p;
    }
    std::string ids;
    for (const PlannedPass& p : mPasses) ids += (ids.empty() ? "" : ", ") + p.id;
    throw Error("pass plan: no pass '" + std::string(id) + "' (passes: " + ids + ")");
}

} // namespace bl
