// The Python module `photon`: the library face (core/render) for scripts. Scenes come as a path,
// JSON text or a dict in the scene format; settings as keyword arguments named as in scene files'
// "render" block (the CLI's long options with '_' for '-'), parsed and checked by the settings
// table itself (core/settings/setting_specs.h), so no setting is spelled here. Images come back
// as NumPy arrays (height, width, 3) of float32 linear radiance: strided views of the readback's
// own pixels, the one copy from the device. Bad input raises ValueError and a runtime failure
// RuntimeError, with the messages the CLI prints; rendering releases the GIL, a progress callback
// sees each frame and may stop the render, and Ctrl-C raises KeyboardInterrupt after the frame in
// flight.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>

#include "core/frame/scene_settings.h"
#include "core/image/image.h"
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

// A scene from a path (a scene or model file), JSON text, or a dict in the scene format.
Scene loadScene(const py::object& scene) {
    if (py::isinstance<py::dict>(scene)) {
        std::string text = py::module_::import("json").attr("dumps")(scene).cast<std::string>();
        return loadSceneJson(text, "<dict>", "", defaultFileReader());
    }
    if (!py::isinstance<py::str>(scene) && !py::hasattr(scene, "__fspath__")) {
        throw InputError("scene: expected a path, JSON text or a dict");
    }
    std::string text = py::str(py::module_::import("os").attr("fspath")(scene));
    std::size_t first = text.find_first_not_of(" \t\r\n");
    if (first != std::string::npos && text[first] == '{') {
        return loadSceneJson(text, "<json>", "", defaultFileReader());
    }
    return loadSceneFile(text);
}

// The keyword arguments: backend, device, time, and every render setting by its scene-file key.
Options readOptions(const Scene& scene, const py::kwargs& kwargs) {
    Options o;
    o.settings = scene.render;
    bool framesGiven = isGiven(o.settings, "frames");
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
        if (name == "time") {
            o.job.seconds = parseNumber(py::str(value), Range{0.001, 1e6}, "time");
            continue;
        }
        const SettingSpec* spec = findSetting(name);
        if (spec == nullptr || name != spec->key) {
            throw InputError(name + ": no such setting (the keys of a scene file's \"render\" block, as photon-render --help lists them)");
        }
        std::string text = py::str(value);
        if (py::isinstance<py::bool_>(value)) {  // True/False: a flag's true/false, an off|on choice's on/off
            bool onOff = spec->kind == SettingKind::Choice && ("|" + spec->choices + "|").find("|on|") != std::string::npos &&
                         ("|" + spec->choices + "|").find("|off|") != std::string::npos;
            text = value.cast<bool>() ? (onOff ? "on" : "true") : (onOff ? "off" : "false");
        }
        setSetting(o.settings, *spec, text, name);
        framesGiven |= name == "frames";
    }
    o.job.framesCap = framesGiven;
    bool timed = o.job.seconds > 0.0;
    chooseDefaults(o.settings, timed);
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

// Any strides (a view such as render()'s arrays is read in place), any float dtype (converted).
Image fromArray(const py::array_t<float, py::array::forcecast>& array) {
    if (array.ndim() != 3 || array.shape(2) < 3 || array.shape(0) <= 0 || array.shape(1) <= 0) {
        throw InputError("image: expected an array of shape (height, width, 3)");
    }
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

// render(): `progress(frames done, seconds since the start)` after each frame, with the GIL; its
// returning False (the object itself, not a falsy value) cancels, and the image of the frames so far
// comes back. Ctrl-C raises KeyboardInterrupt after the frame in flight; an exception the callback
// raises ends the render and comes through.
py::array_t<float> renderScene(const py::object& sceneArg, const py::object& progress, const py::kwargs& kwargs) {
    Scene scene = loadScene(sceneArg);
    Options o = readOptions(scene, kwargs);
    if (o.job.seconds == 0.0 && !o.job.framesCap) {
        o.job.seconds = kDefaultRenderSeconds;  // as photon-render: no length given anywhere
    }
    bool stopAsked = false;  // progress returned False
    bool signalled = false;  // Ctrl-C: a KeyboardInterrupt is set
    RenderObserver observer;
    if (!progress.is_none()) {
        observer.frame = [&](std::uint32_t frames, double seconds) {
            py::gil_scoped_acquire gil;
            stopAsked = progress(frames, seconds).ptr() == Py_False;
        };
    }
    observer.cancel = [&] {
        signalled = interrupted();
        return signalled || stopAsked;
    };
    RenderResult result;
    {
        py::gil_scoped_release release;
        result = render(std::move(scene), o.settings, o.job, observer);
    }
    if (signalled) {
        throw py::error_already_set();  // the KeyboardInterrupt PyErr_CheckSignals set
    }
    return toArray(std::move(result.image));
}

// Progressive rendering: a backend that keeps its frames between calls.
class ProgressiveRenderer {
public:
    ProgressiveRenderer(const py::object& sceneArg, const py::kwargs& kwargs) {
        Scene scene = loadScene(sceneArg);
        Options o = readOptions(scene, kwargs);
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
        for (std::uint32_t f = 0; f < frames; ++f) {
            {
                py::gil_scoped_release release;
                backend_->renderFrame();
            }
            frames_ += 1;
            bool stop = !progress.is_none() && progress(f + 1, frames).ptr() == Py_False;
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
        Image image;
        {
            py::gil_scoped_release release;
            image = backend_->image();
        }
        return toArray(std::move(image));
    }

    py::dict aovs() {
        if (!backend_->settings().aov) {
            throw InputError("aovs: the renderer keeps no auxiliary images (Renderer(..., aov=True))");
        }
        auto a = std::make_unique<AovImages>(
            aovImages(backend_->readAovs(), backend_->settings().width, backend_->settings().height, frames_));
        py::capsule owner(a.get(), [](void* p) { delete static_cast<AovImages*>(p); });  // the four arrays' one base
        AovImages* held = a.release();
        py::dict out;
        out["albedo"] = viewOf(held->albedo, owner);
        out["normal"] = viewOf(held->normal, owner);
        out["depth"] = viewOf(held->depth, owner);
        out["variance"] = viewOf(held->variance, owner);
        return out;
    }

    // photon-render's --stats file for the frames so far: backend, device, scene costs, each map's
    // photons and grid (the last frame's), and the frames and the last frame's stage times.
    py::object stats() {
        nlohmann::json j = renderStatsJson(*backend_);
        j["frames"] = frames_;
        const FrameStats& last = backend_->lastFrameStats();
        for (const StageInfo& stage : kStages) {
            j["stage_ms"][stage.name] = last.ms[stage.id];
        }
        return py::module_::import("json").attr("loads")(j.dump());
    }

private:
    std::unique_ptr<Renderer> backend_;
    std::uint32_t frames_ = 0;
};

}  // namespace
}  // namespace photon

PYBIND11_MODULE(photon, m) {
    using namespace photon;
    m.doc() = "Photon: GPU photon mapping (CUDA, Vulkan, CPU) from Python; docs/python.md";
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) {
                std::rethrow_exception(p);
            }
        } catch (const InputError& e) {
            PyErr_SetString(PyExc_ValueError, printable(e.what()).c_str());
        } catch (const RuntimeError& e) {
            PyErr_SetString(PyExc_RuntimeError, printable(e.what()).c_str());
        }
    });
    m.def("render", &renderScene, py::arg("scene"), py::kw_only(), py::arg("progress") = py::none(),
          "Renders a scene (a path, JSON text or a dict) and returns its image, (height, width, 3) float32 "
          "linear radiance, a strided view of the readback. Keyword arguments: progress (called as "
          "progress(frames_done, seconds) after each frame; returning False stops the render, which returns "
          "the frames so far), backend, device, time (seconds), and any render setting by its scene-file key "
          "(photons, frames, estimator, seed, deterministic, ...).");
    m.def("devices", &compiledBackends, "The backends compiled into this module (cpu, cuda, vulkan).");
    m.def(
        "write_image",
        [](const std::string& path, const py::array_t<float, py::array::forcecast>& array,
           float exposure) {
            Image image = fromArray(array);
            if (!allFinite(image)) {
                throw InputError(path + ": the image holds values that are not finite (NaN or infinity); nothing was written");
            }
            writeImage(path, image, exposure, Tonemap::Aces);
        },
        py::arg("path"), py::arg("image"), py::arg("exposure") = 0.0f,
        "Writes an image as photon-render does, by extension: .png (tone-mapped sRGB), .exr or .pfm (linear).");
    m.def(
        "read_image", [](const std::string& path) { return toArray(readImage(path)); }, py::arg("path"),
        "Reads a .pfm or .exr file (linear radiance, as photon-render writes them) into (height, width, 3) float32.");
    py::class_<ProgressiveRenderer>(m, "Renderer", "Progressive rendering: frames accumulate across step() calls.")
        .def(py::init<const py::object&, const py::kwargs&>(), py::arg("scene"))
        .def("step", &ProgressiveRenderer::step, py::arg("frames") = 1, py::arg("progress") = py::none(),
             "Renders frames, calling progress(frames_done, frames) after each (returning False stops); "
             "returns the frames accumulated so far.")
        .def("image", &ProgressiveRenderer::image, "The accumulated image (denoised where the settings say).")
        .def("aovs", &ProgressiveRenderer::aovs, "Albedo, normal, depth and variance images (with aov=True).")
        .def("stats", &ProgressiveRenderer::stats, "photon-render's --stats as a dict: photons and grids of the last frame, costs.");
}
