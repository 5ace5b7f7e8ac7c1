// bundlelab view SCENE --mode M [--set k=v ...] [--width W --height H] [--seed S] [--scene-time T]
//                [--fps F] [--play] [--frame-iterations N] [--exposure E] [--script FILE]
//                [--frame-log FILE.csv] [--device D] [--validation]
// A window on one mode's estimate. Progressive: iterations accumulate while the camera rests and
// the estimate restarts when it moves or a setting changes; --play (or SPACE) plays a keyframed
// scene, each frame a new estimate of --frame-iterations iterations at its scene time (the real-time
// modes' one frame per refresh). The iterations are render's (FrameSchedule), so a still frame
// equals `bundlelab render` with the same camera, seed and iterations.
#include "base/Error.h"
#include "base/Log.h"
#include "cli/Commands.h"
#include "cli/FiniteRange.h"
#include "cli/OutputFiles.h"
#include "image/ImageIO.h"
#include "modes/FrameSchedule.h"
#include "modes/Registry.h"
#include "scene/SceneLoader.h"
#include "viewer/CameraControl.h"
#include "viewer/Presenter.h"
#include "viewer/TextOverlay.h"
#include "viewer/ViewScript.h"
#include "viewer/Window.h"
#include "vk/Context.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>

namespace bl::cli {

namespace {

struct ViewOptions {
    std::string scene;
    std::string mode;
    int width = 0;
    int height = 0;
    std::uint64_t seed = 0;
    double sceneTime = 0.0;
    double frameRate = kDefaultFrameRate;
    bool play = false;
    std::uint32_t frameIterations = 1;
    std::uint32_t maxIterations = 0; // 0: keep refining while the camera rests
    double exposure = 0.0;
    std::string script;
    std::string frameLog;
    std::string device;
    bool validation = false;
    std::vector<std::string> assignments;
};

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point start) {
    return std::chrono::duration<double, std::milli>(Clock::now() - start).count();
}

// One viewing session: the window, the device, the mode and what the user changed.
class ViewSession {
public:
    explicit ViewSession(const ViewOptions& o)
        : mOptions(o), mAssignments(o.assignments), mExposure(o.exposure), mPlaying(o.play) {
        // Temporal caches (bidir) are reprojected into each cache's camera: here the camera moves by
        // hand, which the plan cannot know from the scene, so the warp runs always (for a camera at
        // rest the image is the same to the bit, tests/modes/bidir/InterleavingTest.cpp).
        mMode = createViewMode(mAssignments); // bad settings fail before a window opens
        mScene = loadScene(o.scene);
        if (o.width > 0) mScene.camera.resolution.x = o.width;
        if (o.height > 0) mScene.camera.resolution.y = o.height;
        mSchedule = FrameSchedule{1u << 30, o.frameRate, o.sceneTime};
        mSchedule.validate("--fps/--scene-time");
        if (!o.script.empty()) mScript = viewer::loadViewScript(o.script);
        mControl = std::make_unique<viewer::CameraControl>(mScene.bounds().radius());
        mWindow = std::make_unique<viewer::Window>(mScene.camera.resolution.x, mScene.camera.resolution.y,
                                                  "bundlelab view: " + o.mode);
        vk::ContextOptions co{o.device, o.validation};
        co.instanceExtensions = viewer::Window::requiredInstanceExtensions();
        co.swapchain = true;
        mContext = std::make_unique<vk::Context>(co);
        std::cout << "device: " << mContext->info().describe() << "\n";
        mPresenter = std::make_unique<viewer::Presenter>(*mContext, mWindow->createSurface(mContext->instance()),
                                                         std::uint32_t(mScene.camera.resolution.x),
                                                         std::uint32_t(mScene.camera.resolution.y));
        if (!o.frameLog.empty()) {
            mLog.open(o.frameLog);
            if (!mLog) throw Error(o.frameLog + ": cannot write the frame log");
            mLog << "frame,scene_time,iterations,iterate_ms,resolve_ms,present_ms\n";
        }
        for (const std::string& w : lightsLeftOut(*mMode, mScene)) log::warn(w);
        restart();
    }

    ~ViewSession() {
        mMode.reset(); // its GPU objects before the presenter and the device
        mPresenter.reset();
    }

    int run() {
        auto last = Clock::now();
        while (!mQuit) {
            const double seconds = std::chrono::duration<double>(Clock::now() - last).count();
            last = Clock::now();
            for (const viewer::InputEvent& e : mWindow->poll()) handle(e);
            if (!mScript.empty()) {
                while (mScriptStep < mScript.size() && !mQuit && runScript(mScript[mScriptStep])) ++mScriptStep;
                if (mScriptStep == mScript.size()) mQuit = true; // a script closes the window when it ends
            }
            if (mQuit) break;
            if (mControl->fly(*mWindow, seconds, mScene.camera.pose)) moved();
            frame();
        }
        // Everything on the device goes before the device does, so that validation reports any
        // object still alive when the window closes (and the run fails).
        mMode.reset();
        mPresenter.reset();
        mContext->close();
        if (mContext->validationErrorCount() > 0) {
            std::cerr << "bundlelab: " << mContext->validationErrorCount() << " Vulkan validation errors\n";
            return 3;
        }
        return mScriptFailed ? 1 : 0;
    }

private:
    // The mode with `assignments` (throws the CLI's error for a bad one). Temporal caches (bidir)
    // are reprojected into each cache's camera: here the camera moves by hand, which the plan
    // cannot know from the scene, so with temporal = on the warp runs always unless the user chose
    // (for a camera at rest the image is the same to the bit, tests/modes/bidir/InterleavingTest.cpp).
    std::unique_ptr<Mode> createViewMode(std::vector<std::string>& assignments) const {
        std::unique_ptr<Mode> mode = createMode(mOptions.mode, assignments);
        const auto resolved = mode->settings().resolved();
        const bool temporal = std::any_of(resolved.begin(), resolved.end(), [](const auto& kv) {
            return kv.first == "temporal" && kv.second == "on";
        });
        const bool chosen = std::any_of(assignments.begin(), assignments.end(),
                                        [](const std::string& a) { return a.rfind("reprojection=", 0) == 0; });
        if (temporal && !chosen) {
            assignments.push_back("reprojection=always");
            mode = createMode(mOptions.mode, assignments);
            log::info("view: temporal caches reprojected always (reprojection=always): the camera moves by hand");
        }
        return mode;
    }

    // A new estimate: after a camera move, a setting, or the next played frame.
    void restart() {
        mMode->setScene(mScene, mContext.get());
        mIterations = 0;
        mImages.reset();
    }

    void moved() {
        mScene.camera.keys.clear(); // the user's camera replaces a keyframed one
        if (mMode->viewIndependent() && !mPlaying) {
            mImages.reset(); // the same estimate, resolved again from the new camera
        } else {
            mRestart = true;
        }
    }

    // One refresh: restart if needed, one iteration while there is budget, then show it.
    void frame() {
        if (mPlaying && mIterations > 0) { // the next played frame: a new estimate at its time
            ++mFrame;
            mRestart = true;
        }
        if (mRestart) {
            restart();
            mRestart = false;
        }
        double iterateMs = 0.0, resolveMs = 0.0;
        const std::uint32_t budget = mPlaying ? mOptions.frameIterations : mOptions.maxIterations;
        const bool more = budget == 0 || mIterations < budget;
        if (more) {
            const auto start = Clock::now();
            const std::uint32_t count = mPlaying ? mOptions.frameIterations : 1u;
            for (std::uint32_t i = 0; i < count; ++i) {
                mMode->iterate(mSchedule.iteration(mFrame, mIterations, mOptions.seed));
                ++mIterations;
            }
            iterateMs = msSince(start);
            mLastIterateMs = iterateMs / double(count);
        }
        if (more || !mImages) {
            const auto start = Clock::now();
            mImages = std::make_unique<ImageSet>(mMode->resolve());
            resolveMs = msSince(start);
        }
        const auto start = Clock::now();
        const Rgba8Image shown = compose();
        mPresenter->present(shown.texels, std::uint32_t(shown.width), std::uint32_t(shown.height));
        mShown = shown;
        if (mLog) {
            mLog << mFrame << "," << mSchedule.timeOf(mFrame) << "," << mIterations << "," << iterateMs << ","
                 << resolveMs << "," << msSince(start) << "\n";
        }
        ++mRefreshes;
    }

    const std::pair<std::string, Image>& shownLayer() const {
        mLayer = mLayer % mImages->layers.size();
        return mImages->layers[mLayer];
    }

    Rgba8Image compose() const {
        const auto& [name, image] = shownLayer();
        Rgba8Image f = toSrgb8(image, float(mExposure));
        if (mOverlay == 0) return f;
        std::ostringstream t;
        t << mOptions.mode << "  layer " << (name.empty() ? "radiance" : name) << "  exposure " << mExposure << "  "
          << (mControl->style() == viewer::CameraControl::Style::Orbit ? "orbit" : "fly") << "\n";
        t << mIterations << " iterations  " << mLastIterateMs << " ms/iteration  scene time "
          << mSchedule.timeOf(mFrame) << (mPlaying ? " (playing)" : "") << "\n";
        const std::vector<ParamSpec> params = findMode(mOptions.mode).parameters();
        if (mOverlay == 2) {
            for (const PassTime& p : mMode->timings()) t << "  " << p.name << " " << p.meanMs() << " ms\n";
            for (const PlannedPass& p : mMode->plan(mScene)) {
                t << (p.runs ? "  run  " : "  skip ") << p.id << ": " << p.code << "\n";
            }
        }
        if (!params.empty() && mOverlay == 2) {
            const ParamSpec& selected = params[mSelected % params.size()];
            t << "[TAB] " << selected.key << " = " << currentValue(selected.key) << "  ([ ] to change)\n";
        }
        if (!mMessage.empty()) t << mMessage << "\n";
        viewer::drawText(f, 4, 4, t.str(), f.width >= 512 ? 2 : 1);
        return f;
    }

    std::string currentValue(const std::string& key) const {
        for (const auto& [k, v] : mMode->settings().resolved()) {
            if (k == key) return v;
        }
        return "?";
    }

    // A setting changed live: validated by creating the mode with it (the CLI's own check and
    // error text); on success the estimate restarts with the new mode.
    bool setSetting(const std::string& assignment) {
        const std::string key = assignment.substr(0, assignment.find('='));
        std::vector<std::string> next;
        for (const std::string& a : mAssignments) {
            if (a.substr(0, a.find('=')) != key) next.push_back(a);
        }
        next.push_back(assignment);
        try {
            std::unique_ptr<Mode> mode = createViewMode(next);
            mMode = std::move(mode);
            mAssignments = next;
            mMessage = "set " + assignment;
            mRestart = true;
            return true;
        } catch (const Error& e) {
            mMessage = std::string("bundlelab: error: ") + e.what();
            std::cerr << mMessage << "\n";
            return false;
        }
    }

    // [ and ]: the selected parameter's previous or next value (choices in order, booleans
    // flipped, numbers halved or doubled within their range).
    void stepSetting(int direction) {
        const std::vector<ParamSpec> params = findMode(mOptions.mode).parameters();
        if (params.empty()) return;
        const ParamSpec& p = params[mSelected % params.size()];
        const std::string now = currentValue(p.key);
        std::string value;
        if (!p.choices.empty()) {
            auto it = std::find(p.choices.begin(), p.choices.end(), now);
            const std::size_t i = it == p.choices.end() ? 0 : std::size_t(it - p.choices.begin());
            value = p.choices[(i + p.choices.size() + std::size_t(direction + int(p.choices.size()))) % p.choices.size()];
        } else if (std::holds_alternative<bool>(p.defaultValue)) {
            value = now == "true" ? "false" : "true";
        } else if (std::holds_alternative<std::int64_t>(p.defaultValue)) {
            const double v = std::stod(now);
            const double stepped = direction > 0 ? std::max(v * 2.0, v + 1.0) : std::floor(v / 2.0);
            value = std::to_string(std::int64_t(std::clamp(stepped, p.min, p.max)));
        } else if (std::holds_alternative<double>(p.defaultValue)) {
            const double v = std::stod(now);
            const double stepped = v == 0.0 ? (direction > 0 ? 0.1 : 0.0) : (direction > 0 ? v * 2.0 : v / 2.0);
            value = formatValue(ParamValue(std::clamp(stepped, p.min, p.max)));
        } else {
            return;
        }
        setSetting(p.key + "=" + value);
    }

    void handle(const viewer::InputEvent& e) {
        using Kind = viewer::InputEvent::Kind;
        if (e.kind == Kind::Close) {
            mQuit = true;
            return;
        }
        if (e.kind != Kind::Key) {
            if (mControl->apply(e, mScene.camera.pose)) moved();
            return;
        }
        const std::string& k = e.key;
        if (k == "ESCAPE") mQuit = true;
        else if (k == "L") mLayer = mImages ? (mLayer + (e.shift ? mImages->layers.size() - 1 : 1)) % mImages->layers.size() : 0;
        else if (k == "EQUAL") mExposure += 0.5;
        else if (k == "MINUS") mExposure -= 0.5;
        else if (k == "C") mControl->toggleStyle();
        else if (k == "O") mOverlay = (mOverlay + 1) % 3;
        else if (k == "R") mRestart = true;
        else if (k == "SPACE") mPlaying = !mPlaying;
        else if (k == "TAB") mSelected += e.shift ? findMode(mOptions.mode).parameters().size() - 1 : 1;
        else if (k == "LEFT_BRACKET") stepSetting(-1);
        else if (k == "RIGHT_BRACKET") stepSetting(+1);
        else if (k == "P") std::cout << viewer::CameraControl::tomlBlock(mScene.camera, mScene.origin) << std::flush;
    }

    // Runs a script command; false while it waits (iterate, frames) for more refreshes.
    bool runScript(const viewer::ScriptCommand& c) {
        const std::string where = mOptions.script + ":" + std::to_string(c.line) + ": ";
        bool done = true;
        if (c.verb == "pose") {
            const glm::vec3 origin(mScene.origin);
            mScene.camera.pose.position = glm::vec3(c.numbers[0], c.numbers[1], c.numbers[2]) - origin;
            mScene.camera.pose.target = glm::vec3(c.numbers[3], c.numbers[4], c.numbers[5]) - origin;
            if (c.numbers.size() == 9) mScene.camera.pose.up = glm::vec3(c.numbers[6], c.numbers[7], c.numbers[8]);
            moved();
        } else if (c.verb == "key") {
            viewer::InputEvent e;
            e.shift = c.text.rfind("SHIFT+", 0) == 0;
            e.key = e.shift ? c.text.substr(6) : c.text;
            handle(e);
        } else if (c.verb == "drag" || c.verb == "scroll") {
            viewer::InputEvent e;
            e.kind = c.verb == "drag" ? viewer::InputEvent::Kind::Drag : viewer::InputEvent::Kind::Scroll;
            e.button = c.right ? 1 : 0;
            e.dx = c.verb == "drag" ? c.numbers[0] : 0.0;
            e.dy = c.verb == "drag" ? c.numbers[1] : c.numbers[0];
            handle(e);
        } else if (c.verb == "set") {
            if (!setSetting(c.text)) mScriptFailed = true;
        } else if (c.verb == "iterate") {
            const auto n = std::uint32_t(c.numbers[0]);
            const std::uint32_t limit = mPlaying ? mOptions.frameIterations : mOptions.maxIterations;
            if (limit > 0 && n > limit) {
                throw Error(where + "iterate " + std::to_string(n) + ": an estimate here stops at " + std::to_string(limit) +
                            (mPlaying ? " iterations per played frame (--frame-iterations)" : " iterations (--max-iterations)"));
            }
            done = !mRestart && mIterations >= n;
            if (done && mIterations > std::uint32_t(c.numbers[0])) {
                throw Error(where + "iterate " + std::to_string(std::uint32_t(c.numbers[0])) + ": the estimate already holds " +
                            std::to_string(mIterations) + " iterations (use --max-iterations, or restart with key R)");
            }
        } else if (c.verb == "frames") {
            if (mFramesLeft < 0) mFramesLeft = int(c.numbers[0]);
            done = mFramesLeft-- <= 0;
            if (done) mFramesLeft = -1;
        } else if (c.verb == "screenshot") {
            done = !mRestart; // after a move or a setting: the new estimate, not the last one
            if (done) screenshot(c.text);
        } else if (c.verb == "quit") {
            mQuit = true;
        }
        return done;
    }

    void screenshot(const std::string& path) {
        if (!mImages) mImages = std::make_unique<ImageSet>(mMode->resolve());
        RenderRecord record{mOptions.scene, mOptions.mode, mContext->info().describe(), mOptions.seed};
        record.frame = mFrame;
        record.sceneTime = mSchedule.timeOf(mFrame);
        for (const std::string& f : writeRenderOutputs(path, *mImages, *mMode, record)) std::cout << "wrote " << f << "\n";
        const std::string view = std::filesystem::path(path).replace_extension(".view.png").string();
        writePng(view, compose());
        std::cout << "wrote " << view << "\n";
    }

    ViewOptions mOptions;
    std::vector<std::string> mAssignments;
    Scene mScene;
    FrameSchedule mSchedule;
    std::vector<viewer::ScriptCommand> mScript;
    std::size_t mScriptStep = 0;
    int mFramesLeft = -1;
    bool mScriptFailed = false;
    // Declared in the order they must be destroyed last-first: window, device, presenter, mode.
    std::unique_ptr<viewer::Window> mWindow;
    std::unique_ptr<vk::Context> mContext;
    std::unique_ptr<viewer::Presenter> mPresenter;
    std::unique_ptr<Mode> mMode;
    std::unique_ptr<viewer::CameraControl> mControl;
    std::unique_ptr<ImageSet> mImages;
    Rgba8Image mShown;
    std::ofstream mLog;
    std::uint32_t mIterations = 0;
    std::uint32_t mFrame = 0;
    std::uint64_t mRefreshes = 0;
    double mLastIterateMs = 0.0;
    double mExposure = 0.0;
    mutable std::size_t mLayer = 0;
    std::size_t mSelected = 0;
    bool mPlaying = false;
    bool mRestart = false;
    int mOverlay = 1; // 0: off, 1: two lines (and messages), 2: also pass times, plan and settings
    bool mQuit = false;
    std::string mMessage;
};

} // namespace

void addViewCommand(CLI::App& app, Action& action) {
    auto o = std::make_shared<ViewOptions>();
    CLI::App* cmd = app.add_subcommand("view", "a window on one mode: camera, live settings, progressive or played frames");
    cmd->add_option("scene", o->scene, "scene file (.toml, Mitsuba .xml, glTF, or a bare .obj/.ply)")->required();
    cmd->add_option("-m,--mode", o->mode, "rendering mode (see `bundlelab modes`)")->required();
    cmd->add_option("--width", o->width, "image width (overrides the scene's camera)")->check(CLI::Range(1, 8192));
    cmd->add_option("--height", o->height, "image height (overrides the scene's camera)")->check(CLI::Range(1, 8192));
    cmd->add_option("--seed", o->seed, "run seed");
    cmd->add_option("--scene-time", o->sceneTime, "scene time in seconds (of the first played frame)")
        ->check(finiteRange(-1e9, 1e9));
    cmd->add_option("--fps", o->frameRate, "frames per second of scene time when playing (default 24)")
        ->check(finiteRange(1e-6, 1e6));
    cmd->add_flag("--play", o->play, "start playing the keyframed scene (SPACE toggles)");
    cmd->add_option("--frame-iterations", o->frameIterations, "iterations per played frame (default 1)")
        ->check(CLI::Range(1u, 1u << 20));
    cmd->add_option("--max-iterations", o->maxIterations, "stop refining a still estimate after N iterations (0: never)")
        ->check(CLI::Range(0u, 1u << 30));
    cmd->add_option("--exposure", o->exposure, "display exposure in stops (= and - change it)")->check(finiteRange(-64, 64));
    cmd->add_option("--script", o->script, "run a script of poses, keys and screenshots, then close (viewer/ViewScript.h)");
    cmd->add_option("--frame-log", o->frameLog, "write each shown frame's times to this CSV");
    cmd->add_option("--device", o->device, "Vulkan device: index or name substring (default: a GPU, else lavapipe)");
    cmd->add_flag("--validation", o->validation, "enable Vulkan validation layers; errors fail the run");
    cmd->add_option("--set", o->assignments, "mode parameter key=value (repeatable)");
    cmd->callback([o, &action] {
        action = [o] {
            if (!findMode(o->mode).needsGpu) {
                // The reference tracer needs no device, but the window does: one is made for it.
                log::info("view: " + o->mode + " renders on the CPU; the window presents through Vulkan");
            }
            ViewSession session(*o);
            return session.run();
        };
    });
}

} // namespace bl::cli
