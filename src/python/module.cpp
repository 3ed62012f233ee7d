// The Python module `phos` (docs/python.md): load a scene, render it with any integrator and every
// option of `phos render` as keyword arguments, and get the image, its layers and AOVs as float32
// NumPy arrays; read, write and compare images; the photon maps as arrays. Renders run through
// run_render (app/lib/render_command.h), the function `phos render` runs, so a render here is
// bit-identical to the same render on the command line. A render runs on a thread of its own while
// the calling thread, the GIL released between polls, calls the progress callback and turns Ctrl-C
// into an interrupt request: the render stops and returns what it has, as `phos render` does.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <csignal>
#include <exception>
#include <future>
#include <memory>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "app/lib/photon_cloud.h"
#include "app/lib/photons_command.h"
#include "app/lib/render_command.h"
#include "app/lib/render_options.h"
#include "core/error.h"
#include "core/image.h"
#include "core/interrupt.h"
#include "core/log.h"
#include "core/option_table.h"
#include "core/progress.h"
#include "film/metrics.h"
#include "integrators/registry.h"
#include "io/image/image_io.h"
#include "scene/scene.h"

namespace py = pybind11;

namespace phos::python {
namespace {

using app::BoundTable;
using app::PhotonTrace;
using app::RenderCommand;
using app::RenderHooks;
using app::RenderResult;

// phos.SceneError, created in the module's init.
PyObject* g_scene_error = nullptr;

// Raises phos.SceneError(message) with file, line, column and message attributes.
[[noreturn]] void raise_scene_error(const std::string& text, const std::string& file, int line, int column,
                                    const std::string& message) {
    py::object error = py::reinterpret_borrow<py::object>(g_scene_error)(text);
    error.attr("file") = file;
    error.attr("line") = line;
    error.attr("column") = column;
    error.attr("message") = message;
    PyErr_SetObject(g_scene_error, error.ptr());
    throw py::error_already_set();
}

// Runs `f`, turning phos's errors into Python's: ParseError -> SceneError (with its location),
// InputError -> ValueError (a bad option or value) unless `input_is_scene` (loading: a missing or
// unreadable file is a SceneError too).
template <class F>
auto translate_errors(F&& f, bool input_is_scene = false, const std::string& path = "") {
    try {
        return f();
    } catch (const ParseError& e) {
        raise_scene_error(e.what(), e.file, e.line, e.column, e.message);
    } catch (const InputError& e) {
        if (input_is_scene) raise_scene_error(e.what(), path, 0, 0, e.what());
        throw py::value_error(e.what());
    }
}

// A keyword's value as the option's command-line words.
std::vector<std::string> option_words(const options::Option& o, const py::handle& value) {
    const auto word = [](const py::handle& v) -> std::string {
        if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
        if (py::isinstance<py::float_>(v)) return py::repr(v).cast<std::string>();  // round-trips
        return py::str(v).cast<std::string>();
    };
    const bool sequence = (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value));
    std::vector<std::string> words;
    if (sequence) {
        for (const py::handle& v : value) words.push_back(word(v));
        if (o.arity == 1) {  // a comma-separated list: --aov albedo,normal
            std::string joined;
            for (const std::string& w : words) joined += (joined.empty() ? "" : ",") + w;
            words = {joined};
        }
    } else {
        words.push_back(word(value));
    }
    if (int(words.size()) != o.arity)
        throw py::value_error(options::option_error(o, "expects " + std::to_string(o.arity) + " values (" +
                                                           o.value_name + "), got " +
                                                           std::to_string(words.size())));
    return words;
}

// Sets keyword `key` (underscores for dashes: photons_per_iter; global_ for --global) on `cmd`
// through its option table, with the command line's checks and messages; returns the table's
// title. ValueError for an unknown option or a bad value.
std::string set_option(RenderCommand& cmd, const std::string& key, const py::handle& value) {
    // A trailing underscore is Python's way round its keywords: global_=50000 is --global.
    std::string name = key.size() > 1 && key.back() == '_' ? key.substr(0, key.size() - 1) : key;
    for (char& c : name)
        if (c == '_') c = '-';
    for (const BoundTable& b : cmd.tables()) {
        const options::Option* o = b.table->find(name);
        bool negated = false;
        if (!o)
            for (const options::Option& candidate : b.table->options)
                if (candidate.flag && candidate.negation == name) o = &candidate, negated = true;
        if (!o) continue;
        try {
            if (o->flag) {
                if (!py::isinstance<py::bool_>(value))
                    throw py::value_error(options::option_error(*o, "expects True or False"));
                const bool present = value.cast<bool>() != negated;
                o->set(b.object, {present == o->flag_value ? "true" : "false"});
            } else {
                o->set(b.object, option_words(*o, value));
            }
        } catch (const options::ValueError& e) {
            throw py::value_error(options::option_error(*o, e.what()));
        }
        cmd.given.insert(o->name);
        return b.table->title;
    }
    throw py::value_error("unknown option '" + key +
                          "' (phos.options() lists them; `phos render --help` too)");
}

// A loaded scene and the options it was loaded with.
struct Scene {
    RenderCommand base;
    std::shared_ptr<const scene::Scene> scene;
    std::string path() const { return base.scene_path; }
};

// The scene-reading options (their table changes what is loaded).
bool reads_scene(const std::string& table_title) { return table_title == app::scene_options().title; }

std::shared_ptr<const scene::Scene> load_scene(const RenderCommand& cmd) {
    return translate_errors([&] { return std::make_shared<const scene::Scene>(app::load_render_scene(cmd)); },
                            true, cmd.scene_path);
}

Scene load(const std::string& path, const py::kwargs& overrides) {
    Scene s;
    s.base.scene_path = path;
    s.base.run.quiet = false;
    for (const auto& [key, value] : overrides) set_option(s.base, key.cast<std::string>(), value);
    s.scene = load_scene(s.base);
    return s;
}

// H x W x 3 float32 array of `image` (row 0 at the top).
py::array_t<float> to_array(const Image& image) {
    py::array_t<float> a({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(3)});
    float* out = a.mutable_data();
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) out[i * 3 + size_t(c)] = image.pixels[i][c];
    return a;
}

// An H x W x 3 (or H x W: grey) array of numbers as an image.
Image from_array(const py::handle& value, const char* what) {
    const auto a = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(value);
    if (!a) throw py::value_error(std::string(what) + ": expected an array of numbers");
    const bool grey = a.ndim() == 2;
    if (!grey && !(a.ndim() == 3 && a.shape(2) == 3))
        throw py::value_error(std::string(what) + ": expected an H x W x 3 (or H x W) array, got " +
                              std::to_string(a.ndim()) + " dimensions");
    if (a.shape(0) < 1 || a.shape(1) < 1) throw py::value_error(std::string(what) + ": the image is empty");
    Image image(int(a.shape(1)), int(a.shape(0)));
    const float* in = a.data();
    for (size_t i = 0; i < image.pixels.size(); ++i)
        for (int c = 0; c < 3; ++c) image.pixels[i][c] = grey ? in[i] : in[i * 3 + size_t(c)];
    return image;
}

// An image given as an array or a path.
Image image_of(const py::handle& value, const char* what) {
    if (py::isinstance<py::str>(value)) {
        const std::string path = value.cast<std::string>();
        return translate_errors([&] { return io::read_image(path); });
    }
    return from_array(value, what);
}

py::object render(const Scene& scene, const py::kwargs& kwargs) {
    RenderCommand cmd = scene.base;
    cmd.run.progress = false;
    cmd.given.insert("progress");  // no bar on stderr: progress goes to the callback
    py::object callback = py::none();
    bool reload = false;
    for (const auto& [k, value] : kwargs) {
        const std::string key = k.cast<std::string>();
        if (key == "progress" && !py::isinstance<py::bool_>(value)) {
            if (!value.is_none() && !PyCallable_Check(value.ptr()))
                throw py::value_error("progress: expected a callable(fraction, label) or None");
            callback = py::reinterpret_borrow<py::object>(value);
            continue;
        }
        if (key == "output" || key == "o")
            throw py::value_error("output: phos.render returns the image; write it with phos.write");
        reload |= reads_scene(set_option(cmd, key, value));
    }
    const std::shared_ptr<const scene::Scene> loaded = reload ? load_scene(cmd) : scene.scene;

    RenderResult result;
    Progress progress(Progress::Mode::Off);
    RenderHooks hooks;
    hooks.scene = loaded.get();
    hooks.result = &result;
    hooks.progress = &progress;
    hooks.signal_handlers = false;
    interrupt::reset();
    std::exception_ptr failure;
    int status = 0;
    std::promise<void> finished;
    std::future<void> done = finished.get_future();
    std::thread worker([&] {
        try {
            status = app::run_render(cmd, hooks);
        } catch (...) {
            failure = std::current_exception();
        }
        finished.set_value();
    });
    // The calling thread waits with the GIL released, and every 100 ms takes it to call the
    // callback and to see Ctrl-C (Python's handler only sets a flag that PyErr_CheckSignals reads).
    bool keyboard_interrupt = false;
    py::object callback_error;
    double last_fraction = -2;
    std::string last_label;
    for (;;) {
        bool over;
        {
            py::gil_scoped_release release;
            over = done.wait_for(std::chrono::milliseconds(100)) == std::future_status::ready;
        }
        if (PyErr_CheckSignals() != 0) {
            PyErr_Clear();
            keyboard_interrupt = true;
            interrupt::request(SIGINT);
        }
        if (!callback.is_none() && !callback_error) {
            const Progress::Snapshot s = progress.snapshot();
            if (!s.label.empty() && (s.fraction != last_fraction || s.label != last_label)) {
                last_fraction = s.fraction;
                last_label = s.label;
                try {
                    callback(s.fraction, s.label);
                } catch (py::error_already_set& e) {  // stop the render, raise it afterwards
                    callback_error = py::reinterpret_borrow<py::object>(e.value());
                    interrupt::request();
                }
            }
        }
        if (over) break;
    }
    worker.join();
    interrupt::reset();
    if (callback_error) {
        PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(callback_error.ptr())), callback_error.ptr());
        throw py::error_already_set();
    }
    if (failure) translate_errors([&] { std::rethrow_exception(failure); });

    py::module_ types = py::module_::import("types");
    py::dict out;
    out["image"] = result.image.pixels.empty() ? py::object(py::none()) : py::object(to_array(result.image));
    py::dict layers;
    for (const auto& [name, image] : result.layers) layers[py::str(name)] = to_array(image);
    out["layers"] = layers;
    out["integrator"] = integrators::integrator(result.integrator).name;
    const bool iterations =
        integrators::integrator(result.integrator).counts == integrators::Counts::Iterations;
    out["iterations"] = iterations ? py::object(py::int_(result.done.units)) : py::object(py::none());
    out["spp"] = iterations ? py::object(py::none()) : py::object(py::int_(result.done.units));
    out["time"] = result.seconds;
    out["photons"] = result.photons;
    py::dict rays;
    rays["camera"] = result.rays.camera;
    rays["shadow"] = result.rays.shadow;
    rays["bounce"] = result.rays.bounce;
    rays["photon"] = result.rays.photon;
    out["rays"] = rays;
    out["interrupted"] = result.interrupted || keyboard_interrupt || status != 0;
    out["width"] = cmd.render.width;
    out["height"] = cmd.render.height;
    return types.attr("SimpleNamespace")(**out);
}

void write_array(const py::handle& array, const std::string& path, float exposure) {
    const Image image = from_array(array, "write");
    translate_errors([&] {
        if (!io::is_writable_image_path(path))
            throw InputError("'" + path + "': unknown image format (use .exr, .pfm, .png or .bmp)");
        io::write_image(path, image, {exposure});
    });
}

py::object diff(const py::handle& image, const py::handle& reference) {
    const Image a = image_of(image, "diff image"), b = image_of(reference, "diff reference");
    if (a.width != b.width || a.height != b.height)
        throw py::value_error("diff: the images differ in size (" + std::to_string(a.width) + "x" +
                              std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                              std::to_string(b.height) + ")");
    py::dict out;
    out["relmse"] = film::rel_mse(a, b);
    out["mean_ratio"] = film::mean_ratio(a, b);
    return py::module_::import("types").attr("SimpleNamespace")(**out);
}

py::object photons(const Scene& scene, const py::object& maps, const py::kwargs& kwargs) {
    RenderCommand cmd = scene.base;
    bool reload = false;
    for (const auto& [k, value] : kwargs)
        reload |= reads_scene(set_option(cmd, k.cast<std::string>(), value));
    const std::shared_ptr<const scene::Scene> loaded = reload ? load_scene(cmd) : scene.scene;
    std::vector<int> kinds;
    if (!maps.is_none()) {
        std::string list;
        if (py::isinstance<py::str>(maps)) {
            list = maps.cast<std::string>();
        } else {
            for (const py::handle& m : maps)
                list += (list.empty() ? "" : ",") + py::str(m).cast<std::string>();
        }
        kinds = translate_errors([&] { return app::parse_photon_maps(list); });
    }
    interrupt::reset();
    PhotonTrace traced;
    std::exception_ptr failure;
    {
        py::gil_scoped_release release;
        Stats stats;
        try {
            traced = app::trace_photon_maps(cmd, *loaded, kinds, true, stats);
        } catch (...) {
            failure = std::current_exception();
        }
    }
    if (failure) translate_errors([&] { std::rethrow_exception(failure); });
    // Columns grouped as the cloud names them (photon_cloud.h).
    const auto column = [&](const std::string& name) -> const io::PointColumn* {
        for (const io::PointColumn& c : traced.cloud.columns)
            if (c.name == name) return &c;
        return nullptr;
    };
    const py::ssize_t n = py::ssize_t(traced.cloud.size());
    const auto vectors = [&](const char* a, const char* b, const char* c) {
        py::array_t<float> out({n, py::ssize_t(3)});
        const io::PointColumn* cols[3] = {column(a), column(b), column(c)};
        float* o = out.mutable_data();
        for (py::ssize_t i = 0; i < n; ++i)
            for (int k = 0; k < 3; ++k) o[i * 3 + k] = cols[k] ? cols[k]->floats[size_t(i)] : 0.0f;
        return out;
    };
    const auto bytes = [&](const char* name) -> py::object {
        const io::PointColumn* c = column(name);
        if (!c) return py::none();
        py::array_t<uint8_t> out(n);
        std::copy(c->bytes.begin(), c->bytes.end(), out.mutable_data());
        return out;
    };
    py::dict out;
    out["position"] = vectors("x", "y", "z");
    out["direction"] = vectors("dx", "dy", "dz");
    out["power"] = vectors("power_r", "power_g", "power_b");
    out["normal"] = vectors("nx", "ny", "nz");
    out["map"] = bytes("map");
    out["bounces"] = bytes("bounces");
    py::list names;
    for (int m = 0; m < photon::kMapCount; ++m) names.append(app::photon_map_label(m));
    out["map_names"] = names;
    py::dict emitted;
    for (const int m : traced.kinds) emitted[app::photon_map_label(m)] = traced.maps.emitted[m];
    out["emitted"] = emitted;
    out["interrupted"] = traced.interrupted;
    return py::module_::import("types").attr("SimpleNamespace")(**out);
}

// Every option: name (with underscores) -> its help line.
py::dict option_list() {
    py::dict out;
    for (const options::Table* t : app::all_tables())
        for (const options::Option& o : t->options) {
            if (o.hidden) continue;
            std::string key = o.name;
            for (char& c : key)
                if (c == '-') c = '_';
            out[py::str(key)] = o.help;
        }
    return out;
}

}  // namespace
}  // namespace phos::python

PYBIND11_MODULE(phos, m) {
    using namespace phos::python;
    namespace py = pybind11;
    m.doc() = "phos: a photon-mapping renderer (docs/python.md)";
    static py::exception<phos::ParseError> scene_error(m, "SceneError", PyExc_ValueError);
    g_scene_error = scene_error.ptr();

    py::class_<Scene>(m, "Scene", "a scene loaded by phos.load")
        .def_property_readonly("path", &Scene::path)
        .def_property_readonly("width", [](const Scene& s) { return s.scene->settings.width.value_or(512); })
        .def_property_readonly("height",
                               [](const Scene& s) { return s.scene->settings.height.value_or(512); })
        .def("__repr__", [](const Scene& s) { return "<phos.Scene '" + s.path() + "'>"; });

    m.def("load", &load, py::arg("path"),
          "Loads a .scn, .scene or .pbrt scene; keyword arguments are render options kept for every "
          "render of it (phos.options()). Raises phos.SceneError (file, line, column, message).");
    m.def("render", &render, py::arg("scene"),
          "Renders `scene`; every option of `phos render` is a keyword argument (integrator, spp, time, "
          "seed, threads, layers, aov, ...), and progress=callable(fraction, label). Returns a namespace "
          "with image (H x W x 3 float32, linear), layers (dict of arrays), integrator, spp or "
          "iterations, time, photons, rays and interrupted.");
    m.def("write", &write_array, py::arg("image"), py::arg("path"), py::arg("exposure") = 0.0f,
          "Writes an H x W x 3 array as .exr, .pfm, .png or .bmp (PNG/BMP: sRGB, after `exposure` stops).");
    m.def(
        "read",
        [](const std::string& path) {
            return to_array(translate_errors([&] { return phos::io::read_image(path); }));
        },
        py::arg("path"),
        "Reads an image (.exr, .pfm, .hdr, .png, ...) as an H x W x 3 float32 array, linear.");
    m.def("diff", &diff, py::arg("image"), py::arg("reference"),
          "relMSE and mean ratio of an image against a reference (arrays or paths), as `phos diff`.");
    m.def("photons", &photons, py::arg("scene"), py::arg("maps") = py::none(),
          "Traces the photon maps as `phos photons` does; returns position, direction, power, normal "
          "(N x 3 float32), map and bounces (N uint8), map_names and emitted.");
    m.def("options", &option_list, "Every render option (keyword name -> help).");
    m.def("integrators", [] {
        std::vector<std::string> names;
        for (const auto& i : phos::integrators::integrators()) names.push_back(i.name);
        return names;
    });
}
