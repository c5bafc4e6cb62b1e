// The Python module `photon`: the library face (core/render) for scripts. Scenes come as a path,
// JSON text or a dict in the scene format; settings as keyword arguments named as in scene files'
// "render" block (the CLI's long options with '_' for '-'), parsed and checked by the settings
// table itself (core/settings/setting_specs.h), so no setting is spelled here. Images come back
// as NumPy arrays (height, width, 3) of float32 linear radiance: strided views of the readback's
// own pixels, the one copy from the device. Bad input raises ValueError and a runtime failure
// RuntimeError, with the messages the CLI prints (naming keywords where the CLI names flags);
// what the loaders notice comes as warnings.warn. Rendering releases the GIL, a progress callback
// sees each frame and may stop the render, and Ctrl-C raises KeyboardInterrupt after the frame in
// flight. A Renderer serializes calls on itself: a second thread's call waits for the first.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <memory>
#include <mutex>
#include <optional>
#include <string>

#include "core/frame/scene_settings.h"
#include "core/image/image.h"
#include "core/loaders/environment_loader.h"
#include "core/loaders/model_loader.h"
#include "core/loaders/scene_loader.h"
#include "core/render/devices.h"
#include "core/render/render.h"
#include "core/render/render_stats.h"
#include "core/settings/setting_specs.h"
#include "core/system/error.h"

namespace py = pybind11;

namespace photon {
namespace {

// What render() and Renderer take besides the render settings.
struct Options {
    RenderSettings settings;
    RenderJob job;
};

// Messages as Python callers name things: "--max-depth" becomes "max_depth" (the keyword), for
// every setting's flag and the keywords that are no settings.
std::string pythonNames(const std::string& message) {
    std::string out;
    for (std::size_t i = 0; i < message.size();) {
        bool starts = message.compare(i, 2, "--") == 0 && (i == 0 || message[i - 1] == ' ' || message[i - 1] == '(' ||
                                                           message[i - 1] == '"' || message[i - 1] == '\'');
        std::size_t end = i + 2;
        while (starts && end < message.size() && (std::islower(static_cast<unsigned char>(message[end])) ||
                                                   std::isdigit(static_cast<unsigned char>(message[end])) || message[end] == '-')) {
            ++end;
        }
        std::string flag = message.substr(i, end - i);
        static const char* const kOthers[] = {"--time", "--backend", "--device", "--environment", "--environment-intensity",
                                              "--validation"};
        bool known = starts && end > i + 2 &&
                     (findSetting(flag) != nullptr || std::find(std::begin(kOthers), std::end(kOthers), flag) != std::end(kOthers));
        if (!known) {
            out += message[i++];
            continue;
        }
        std::string keyword = flag.substr(2);
        std::replace(keyword.begin(), keyword.end(), '-', '_');
        out += keyword;
        i = end;
    }
    return out;
}

// Each line as a Python warning (UserWarning, from the caller's line); a filter that turns
// warnings into errors raises here.
void warnPython(const std::vector<std::string>& lines) {
    for (const std::string& line : lines) {
        if (PyErr_WarnEx(PyExc_UserWarning, printable(pythonNames(line)).c_str(), 1) != 0) {
            throw py::error_already_set();
        }
    }
}

void refuseNul(const std::string& path, const char* what) {
    if (path.find('\0') != std::string::npos) {
        throw InputError(std::string(what) + ": the path holds a NUL character");
    }
}

// "/render/photons" of a JSON pointer: '~' and '/' in keys escaped (RFC 6901).
std::string pointerStep(const std::string& pointer, const std::string& key) {
    std::string step;
    for (char c : key) {
        step += c == '~' ? "~0" : c == '/' ? "~1" : std::string(1, c);
    }
    return pointer + "/" + step;
}

// A dict scene as JSON, each value checked where it is: NaN and infinities (JSON has neither),
// keys that are not strings and objects JSON cannot hold are refused by their JSON pointer;
// NumPy scalars and arrays become numbers and lists (their tolist()).
nlohmann::json toJson(const py::handle& value, const std::string& pointer) {
    auto refuse = [&](const std::string& why) { return InputError("<dict>" + (pointer.empty() ? "" : pointer) + ": " + why); };
    if (value.is_none()) {
        return nullptr;
    }
    if (py::isinstance<py::bool_>(value)) {
        return value.cast<bool>();
    }
    if (py::isinstance<py::int_>(value)) {
        try {
            return value.cast<std::int64_t>();
        } catch (const py::cast_error&) {
            throw refuse("an integer beyond 64 bits (" + std::string(py::str(value)) + ")");
        }
    }
    if (py::isinstance<py::float_>(value)) {
        double number = value.cast<double>();
        if (!std::isfinite(number)) {
            throw refuse("not a finite number (got " + std::string(py::str(value)) + "; JSON has no NaN or infinity)");
        }
        return number;
    }
    if (py::isinstance<py::str>(value)) {
        return value.cast<std::string>();
    }
    if (py::isinstance<py::dict>(value)) {
        nlohmann::json object = nlohmann::json::object();
        for (const auto& [key, item] : value.cast<py::dict>()) {
            if (!py::isinstance<py::str>(key)) {
                throw refuse("a key that is not a string (" + std::string(py::repr(key)) + ")");
            }
            std::string name = key.cast<std::string>();
            object[name] = toJson(item, pointerStep(pointer, name));
        }
        return object;
    }
    if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
        nlohmann::json array = nlohmann::json::array();
        std::size_t index = 0;
        for (const auto& item : value) {
            array.push_back(toJson(item, pointer + "/" + std::to_string(index++)));
        }
        return array;
    }
    py::object type = py::type::of(value);
    std::string module = py::hasattr(type, "__module__") ? std::string(py::str(type.attr("__module__"))) : "";
    if (module == "numpy" && py::hasattr(value, "tolist")) {
        return toJson(value.attr("tolist")(), pointer);
    }
    throw refuse("a " + std::string(py::str(type.attr("__name__"))) + " is no JSON value");
}

// A scene from a path (a scene or model file), JSON text, a dict in the scene format, or None
// (the built-in Cornell box); what the loaders noticed is warned of.
Scene loadScene(const py::object& scene) {
    Scene loaded;
    if (scene.is_none()) {
        loaded = defaultScene();
    } else if (py::isinstance<py::dict>(scene)) {
        loaded = loadSceneJson(toJson(scene, "").dump(), "<dict>", "", defaultFileReader());
    } else if (!py::isinstance<py::str>(scene) && !py::hasattr(scene, "__fspath__")) {
        throw InputError("scene: expected a path, JSON text, a dict or None (the built-in Cornell box)");
    } else {
        std::string text = py::str(py::module_::import("os").attr("fspath")(scene));
        std::size_t first = text.find_first_not_of(" \t\r\n");
        if (first != std::string::npos && text[first] == '{') {
            loaded = loadSceneJson(text, "<json>", "", defaultFileReader());
        } else {
            refuseNul(text, "scene");
            loaded = loadSceneFile(text);
        }
    }
    warnPython(loaded.warnings);
    return loaded;
}

// A keyword's setting: by its scene-file key ("max_eye_depth") or its flag's name ("max_depth").
const SettingSpec* keywordSetting(const std::string& name) {
    for (const SettingSpec& spec : settingSpecs()) {
        std::string flag = std::string(spec.flag).substr(2);
        std::replace(flag.begin(), flag.end(), '-', '_');
        if (name == spec.key || name == flag) {
            return &spec;
        }
    }
    return nullptr;
}

// The keyword arguments: backend, device, validation, time, environment (with
// environment_intensity), and every render setting by its scene-file key or its flag's name.
// `stepped`: a Renderer, whose frames step() asks for: no time, and a converging estimator.
Options readOptions(Scene& scene, const py::kwargs& kwargs, bool stepped) {
    Options o;
    o.settings = scene.render;
    bool framesGiven = isGiven(o.settings, "frames");
    std::string environment;
    double intensity = -1.0;
    for (const auto& [key, value] : kwargs) {
        std::string name = py::str(key);
        if (name == "backend") {
            o.job.backend = py::str(value);
            continue;
        }
        if (name == "device") {
            o.job.device.device = py::str(value);
            continue;
        }
        if (name == "validation") {
            if (!py::isinstance<py::bool_>(value)) {
                throw InputError("validation: expected True or False (got " + printable(py::repr(value).cast<std::string>()) + ")");
            }
            o.job.device.validation = value.cast<bool>();
            continue;
        }
        if (name == "time") {
            if (stepped) {
                throw InputError("time: a Renderer renders the frames step() asks for (time is photon.render's)");
            }
            o.job.seconds = parseNumber(py::str(value), Range{0.001, 1e6}, "time");
            continue;
        }
        if (name == "environment") {
            environment = py::str(py::module_::import("os").attr("fspath")(value));
            refuseNul(environment, "environment");
            if (environment.empty()) {
                throw InputError("environment: the path is empty");
            }
            continue;
        }
        if (name == "environment_intensity") {
            intensity = parseNumber(py::str(value), kEnvironmentIntensity, "environment_intensity");
            continue;
        }
        const SettingSpec* spec = keywordSetting(name);
        if (spec == nullptr) {
            throw InputError(name + ": no such keyword (backend, device, validation, time, environment, "
                                    "environment_intensity, and the keys of a scene file's \"render\" block: photon-render --help)");
        }
        std::string text = py::str(value);
        if (py::isinstance<py::bool_>(value)) {  // True/False: a flag's true/false, an off|on choice's on/off
            bool onOff = spec->kind == SettingKind::Choice && ("|" + spec->choices + "|").find("|on|") != std::string::npos &&
                         ("|" + spec->choices + "|").find("|off|") != std::string::npos;
            text = value.cast<bool>() ? (onOff ? "on" : "true") : (onOff ? "off" : "false");
        }
        setSetting(o.settings, *spec, text, name);
        framesGiven |= spec->key == std::string("frames");
    }
    if (intensity >= 0.0 && environment.empty()) {
        throw InputError("environment_intensity: only with environment");
    }
    if (!environment.empty()) {
        lightWithEnvironmentMap(scene, environment, intensity >= 0.0 ? float(intensity) : 1.0f, "environment");
    }
    o.job.framesCap = framesGiven;
    if (!stepped && o.job.seconds == 0.0 && !framesGiven) {
        o.job.seconds = kDefaultRenderSeconds;  // as photon-render: no length given anywhere
    }
    chooseDefaults(o.settings, stepped || o.job.seconds > 0.0);
    chooseSpectral(o.settings, scene);
    validateSettings(o.settings);
    return o;
}

// The array over an image's own pixels, no copy: the image moves into a heap object that a capsule
// owns (the array's base), and the array views its vec4 storage as (height, width, 3) with strides
// (width · 16, 16, 4) bytes, the fourth float of each pixel skipped. `owner` keeps `image` alive:
// an image of several that one capsule holds (aovs()).
static_assert(sizeof(glm::vec4) == 4 * sizeof(float), "the array's strides assume tightly packed vec4 pixels");

py::array_t<float> viewOf(Image& image, const py::capsule& owner) {
    py::ssize_t w = image.width, h = image.height, pixel = sizeof(glm::vec4);
    return py::array_t<float>({h, w, py::ssize_t(3)}, {w * pixel, pixel, py::ssize_t(sizeof(float))},
                              reinterpret_cast<float*>(image.pixels.data()), owner);
}

py::array_t<float> toArray(Image&& image) {
    auto held = std::make_unique<Image>(std::move(image));
    py::capsule owner(held.get(), [](void* p) { delete static_cast<Image*>(p); });
    return viewOf(*held.release(), owner);
}

// Any strides (a view such as render()'s arrays is read in place), floats of any width; three
// channels exactly (an alpha would be dropped without a word), finite exposure in its range.
Image fromArray(const py::array& any) {
    if (any.dtype().kind() != 'f') {
        throw InputError("image: expected an array of floats, linear radiance (got " + std::string(py::str(any.dtype())) +
                         (any.dtype().kind() == 'u' || any.dtype().kind() == 'i' ? "; divide 8-bit values by 255 and decode sRGB first" : "") +
                         ")");
    }
    if (any.ndim() != 3 || any.shape(0) <= 0 || any.shape(1) <= 0 || any.shape(2) != 3) {
        std::string got = any.ndim() == 3 && any.shape(2) == 4 ? " (got 4 channels: pass image[..., :3] to drop alpha)" : "";
        throw InputError("image: expected an array of shape (height, width, 3)" + got);
    }
    py::array_t<float, py::array::forcecast> array = any;
    auto view = array.unchecked<3>();
    Image image(std::uint32_t(array.shape(1)), std::uint32_t(array.shape(0)));
    for (std::uint32_t y = 0; y < image.height; ++y) {
        for (std::uint32_t x = 0; x < image.width; ++x) {
            image.at(x, y) = glm::vec4(view(y, x, 0), view(y, x, 1), view(y, x, 2), 1.0f);
        }
    }
    return image;
}

// Whether Python has a signal to raise (Ctrl-C): asked between frames, with the GIL.
bool interrupted() {
    py::gil_scoped_acquire gil;
    return PyErr_CheckSignals() != 0;
}

// Whether a progress callback's answer stops: False itself, or NumPy's False (numpy.False_),
// but not None (no answer) or another falsy value.
bool saysStop(const py::object& answer) {
    if (answer.ptr() == Py_False) {
        return true;
    }
    py::object type = py::type::of(answer);
    return py::hasattr(type, "__module__") && std::string(py::str(type.attr("__module__"))) == "numpy" &&
           std::string(py::str(type.attr("__name__"))).rfind("bool", 0) == 0 && !answer.cast<bool>();
}

// render(): `progress(frames done, seconds since the start)` after each frame, with the GIL; its
// returning False cancels, and the image of the frames so far comes back. Ctrl-C raises
// KeyboardInterrupt after the frame in flight, with the image so far as the exception's `image`;
// an exception the callback raises ends the render and comes through. Under mpirun the processes
// but the first return None (the image is the first's).
py::object renderScene(const py::object& sceneArg, const py::object& progress, const py::kwargs& kwargs) {
    Scene scene = loadScene(sceneArg);
    Options o = readOptions(scene, kwargs, false);
    std::string source = sceneArg.is_none() ? "<embedded cornell.json>"
                         : py::isinstance<py::dict>(sceneArg) ? "<dict>"
                                                              : std::string(py::str(sceneArg)).substr(0, 200);
    bool stopAsked = false;  // progress returned False
    std::optional<py::error_already_set> interrupt;  // Ctrl-C, seen between frames or in the callback
    RenderObserver observer;
    if (!progress.is_none()) {
        observer.frame = [&](std::uint32_t frames, double seconds) {
            py::gil_scoped_acquire gil;
            try {
                stopAsked = saysStop(progress(frames, seconds));
            } catch (py::error_already_set& e) {
                if (!e.matches(PyExc_KeyboardInterrupt)) {
                    throw;
                }
                interrupt.emplace(std::move(e));
            }
        };
    }
    observer.cancel = [&] {
        if (!interrupt && interrupted()) {
            py::gil_scoped_acquire gil;
            interrupt.emplace();  // fetches the KeyboardInterrupt PyErr_CheckSignals set
        }
        return interrupt || stopAsked ? 1 : 0;
    };
    RenderResult result;
    {
        py::gil_scoped_release release;
        result = render(std::move(scene), o.settings, o.job, observer);
    }
    if (interrupt) {
        if (result.leader) {
            interrupt->value().attr("image") = toArray(std::move(result.image));
        }
        throw *interrupt;
    }
    if (!result.leader) {
        return py::none();
    }
    if (std::string black = nearlyBlackWarning(result.image, o.settings.exposure, source); !black.empty()) {
        warnPython({black});
    }
    return toArray(std::move(result.image));
}

// Progressive rendering: a backend that keeps its frames between calls. Each call holds the
// renderer: another thread's call waits (without the GIL, which the first may need to finish);
// the same thread may call again from a progress callback.
class ProgressiveRenderer {
public:
    ProgressiveRenderer(const py::object& sceneArg, const py::kwargs& kwargs) {
        Scene scene = loadScene(sceneArg);
        Options o = readOptions(scene, kwargs, true);
        backend_ = createRenderer(o.job.backend, o.job.device);
        choosePhotons(o.settings, backend_->runsOnCpu());
        backend_->setScene(std::move(scene));
        backend_->setSettings(o.settings);
        backend_->prepare();
    }

    // Renders `frames` frames; `progress(frames done, of)` after each, whose returning False ends
    // the step there (as render()'s). Ctrl-C stops after the frame in flight, raising
    // KeyboardInterrupt; the renderer stays usable.
    std::uint32_t step(std::uint32_t frames, const py::object& progress) {
        auto held = hold();
        for (std::uint32_t f = 0; f < frames; ++f) {
            {
                py::gil_scoped_release release;
                backend_->renderFrame();
            }
            frames_ += 1;
            bool stop = !progress.is_none() && saysStop(progress(f + 1, frames));
            if (PyErr_CheckSignals() != 0) {
                throw py::error_already_set();
            }
            if (stop) {
                break;
            }
        }
        return frames_;
    }

    py::array_t<float> image() {
        auto held = hold();
        Image image;
        {
            py::gil_scoped_release release;
            image = backend_->image();
        }
        return toArray(std::move(image));
    }

    py::dict aovs() {
        auto held = hold();
        if (!backend_->settings().aov) {
            throw InputError("aovs: the renderer keeps no auxiliary images (Renderer(..., aov=True))");
        }
        std::unique_ptr<AovImages> a;
        {
            py::gil_scoped_release release;
            a = std::make_unique<AovImages>(
                aovImages(backend_->readAovs(), backend_->settings().width, backend_->settings().height, frames_));
        }
        py::capsule owner(a.get(), [](void* p) { delete static_cast<AovImages*>(p); });  // the four arrays' one base
        AovImages* kept = a.release();
        py::dict out;
        out["albedo"] = viewOf(kept->albedo, owner);
        out["normal"] = viewOf(kept->normal, owner);
        out["depth"] = viewOf(kept->depth, owner);
        out["variance"] = viewOf(kept->variance, owner);
        return out;
    }

    // photon-render's --stats file for the frames so far: backend, device, scene costs, each map's
    // photons and grid (the last frame's), and the frames and the last frame's stage times.
    py::object stats() {
        auto held = hold();
        nlohmann::json j = renderStatsJson(*backend_);
        j["frames"] = frames_;
        const FrameStats& last = backend_->lastFrameStats();
        for (const StageInfo& stage : kStages) {
            j["stage_ms"][stage.name] = last.ms[stage.id];
        }
        return py::module_::import("json").attr("loads")(j.dump());
    }

private:
    std::unique_lock<std::recursive_mutex> hold() {
        std::unique_lock<std::recursive_mutex> lock(mutex_, std::try_to_lock);
        if (!lock.owns_lock()) {
            py::gil_scoped_release release;
            lock.lock();
        }
        return lock;
    }

    std::recursive_mutex mutex_;
private:
    std::unique_ptr<Renderer> backend_;
    std::uint32_t frames_ = 0;
};

}  // namespace
}  // namespace photon

PYBIND11_MODULE(photon, m) {
    using namespace photon;
    m.doc() = "Photon: GPU photon mapping (CUDA, Vulkan, CPU) from Python; docs/python.md";
    m.attr("__version__") = PHOTON_VERSION;
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) {
                std::rethrow_exception(p);
            }
        } catch (const InputError& e) {
            PyErr_SetString(PyExc_ValueError, printable(pythonNames(e.what())).c_str());
        } catch (const RuntimeError& e) {
            PyErr_SetString(PyExc_RuntimeError, printable(pythonNames(e.what())).c_str());
        }
    });
    m.def("render", &renderScene, py::arg("scene") = py::none(), py::kw_only(), py::arg("progress") = py::none(),
          "Renders a scene (a path, JSON text, a dict, or None: the built-in Cornell box) and returns its image, "
          "(height, width, 3) float32 linear radiance, a strided view of the readback. Keyword arguments: progress "
          "(called as progress(frames_done, seconds) after each frame; returning False stops the render, which "
          "returns the frames so far), backend, device, validation, time (seconds), environment (an .hdr or .exr "
          "map that lights the scene) and environment_intensity, and any render setting by its scene-file key or "
          "its photon-render flag's name (photons, frames, estimator, seed, deterministic, max_depth, ...). "
          "Ctrl-C raises KeyboardInterrupt after the frame in flight, its `image` the frames so far.");
    m.def("devices", &compiledBackends, "The backends compiled into this module (cpu, cuda, vulkan).");
    m.def(
        "write_image",
        [](const std::string& path, const py::array& array, double exposure) {
            refuseNul(path, "path");
            RenderSettings checked;
            setSettingNumber(checked, *findSetting("exposure"), exposure, formatNumber(exposure), "exposure");
            Image image = fromArray(array);
            if (!allFinite(image)) {
                throw InputError(path + ": the image holds values that are not finite (NaN or infinity); nothing was written");
            }
            writeImage(path, image, checked.exposure, Tonemap::Aces);
        },
        py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0f,
        "Writes an image as photon-render does, by extension: .png (tone-mapped sRGB, exposure in stops), .exr or "
        ".pfm (linear). The image: (height, width, 3) floats, linear radiance.");
    m.def(
        "read_image",
        [](const std::string& path) {
            refuseNul(path, "path");
            return toArray(readImage(path));
        },
        py::arg("path"),
        "Reads a .pfm or .exr file (linear radiance, as photon-render writes them) into (height, width, 3) float32.");
    py::class_<ProgressiveRenderer>(m, "Renderer",
                                    "Progressive rendering: frames accumulate across step() calls, with sppm (which "
                                    "converges) unless an estimator is given. Keyword arguments as render()'s but time "
                                    "and progress. Calls from several threads take turns.")
        .def(py::init<const py::object&, const py::kwargs&>(), py::arg("scene") = py::none())
        .def("step", &ProgressiveRenderer::step, py::arg("frames") = 1, py::arg("progress") = py::none(),
             "Renders frames, calling progress(frames_done, frames) after each (returning False stops); "
             "returns the frames accumulated so far.")
        .def("image", &ProgressiveRenderer::image, "The accumulated image (denoised where the settings say).")
        .def("aovs", &ProgressiveRenderer::aovs, "Albedo, normal, depth and variance images (with aov=True).")
        .def("stats", &ProgressiveRenderer::stats, "photon-render's --stats as a dict: photons and grids of the last frame, costs.");
}
