// The `_zsweep` extension behind `import zsweep` (python/zsweep/__init__.py
// turns scene dicts, numpy arrays and VTK objects into what this takes).
// Everything a render does runs through the same SceneJob (app/scene_job.h)
// as `zsweep render`, so an image here equals the CLI's bit for bit.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstring>
#include <exception>
#include <functional>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "app/reference_scene.h"
#include "app/scene_args.h"
#include "app/scene_job.h"
#include "output/image_io.h"
#include "output/image_compare.h"
#include "python/py_data.h"
#include "python/py_generate.h"
#include "scene/scene.h"

namespace py = pybind11;

namespace zs::python {

namespace {

struct Cancelled : std::runtime_error {
  Cancelled() : std::runtime_error("render interrupted") {}
};

// Runs `work` on a thread of its own with the GIL released, waking every
// 50 ms to let Python see signals: on Ctrl-C (KeyboardInterrupt) `cancel` is
// set, the render stops after the tiles in flight, and the interrupt is
// raised. Exceptions from `work` are rethrown here.
void run_cancellable(const std::function<void(const std::atomic<bool>&)>& work) {
  std::atomic<bool> cancel{false};
  std::exception_ptr err;
  std::mutex mu;
  std::condition_variable cv;
  bool done = false, interrupted = false;
  {
    py::gil_scoped_release nogil;
    std::thread t([&] {
      try {
        work(cancel);
      } catch (...) {
        err = std::current_exception();
      }
      std::lock_guard<std::mutex> lock(mu);
      done = true;
      cv.notify_all();
    });
    std::unique_lock<std::mutex> lock(mu);
    while (!done) {
      if (cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return done; })) break;
      if (interrupted) continue;
      lock.unlock();
      {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) interrupted = true;  // the error indicator now holds the interrupt
      }
      if (interrupted) cancel = true;
      lock.lock();
    }
    lock.unlock();
    t.join();
  }
  if (interrupted) throw py::error_already_set();
  if (err) std::rethrow_exception(err);
}

// Tiles straight into a (height, width, channels) float32 array.
class ArraySink : public TileSink {
 public:
  ArraySink(float* data, const TileGrid& g, const std::atomic<bool>& cancel) : data_(data), g_(g), cancel_(cancel) {}
  void tile(const TileRect& r, const float* px) override {
    if (cancel_) throw Cancelled();
    const size_t c = g_.channels, w = r.x1 - r.x0;
    for (uint32_t y = r.y0; y < r.y1; ++y)
      std::memcpy(data_ + (size_t(y) * g_.width + r.x0) * c, px + size_t(y - r.y0) * w * c, w * c * sizeof(float));
  }

 private:
  float* data_;
  TileGrid g_;
  const std::atomic<bool>& cancel_;
};

struct Options {
  SceneArgs args;
  bool no_culling = false;
  int frames = 1;
};

// model=2 or model="2": a MODEL number, as the scene's spheres.model.
std::string model_number(const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) throw py::type_error("model must be a whole number or a string, not bool");
  if (py::isinstance<py::int_>(v)) {
    const long long n = v.cast<long long>();
    if (n < 0) throw py::value_error("model: " + std::to_string(n) + " is not a model number");
    return std::to_string(n);
  }
  if (py::isinstance<py::str>(v) && !v.cast<std::string>().empty()) return v.cast<std::string>();
  throw py::type_error("model must be a whole number or a string, not " +
                       std::string(py::str(v.get_type().attr("__name__"))));
}

bool flag(const py::handle& v, const std::string& k) {
  if (!py::isinstance<py::bool_>(v))
    throw py::type_error(k + " must be True or False, not " + std::string(py::str(v.get_type().attr("__name__"))));
  return v.cast<bool>();
}

Options options_from(const py::dict& o) {
  Options out;
  SceneArgs& a = out.args;
  a.python = true;
  for (auto kv : o) {
    const std::string k = py::str(kv.first);
    const py::handle v = kv.second;
    if (v.is_none()) continue;
    // A number checked against the command line's range for it (app/scene_args.h).
    auto number = [&](const NumberRange& r) {
      if (py::isinstance<py::bool_>(v) || !(py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v) ||
                                            py::hasattr(v, "__float__")))
        throw py::type_error(k + " must be a number, not " + std::string(py::str(v.get_type().attr("__name__"))));
      const double x = v.cast<double>();
      const std::string why = number_error(x, r);
      if (!why.empty()) throw py::value_error(k + ": " + why);
      return x;
    };
    auto scene_number = [&](const char* cli) { return number(scene_number_range(cli)); };
    if (k == "width") a.width = uint32_t(scene_number("--width"));
    else if (k == "height") a.height = uint32_t(scene_number("--height"));
    else if (k == "threads") a.threads = int(scene_number("--threads"));
    else if (k == "projection") a.projection = v.cast<std::string>();
    else if (k == "memory_budget") a.memory_budget_mb = scene_number("--memory-budget");
    else if (k == "scan") a.scan = v.cast<std::string>();
    else if (k == "variant") a.variant = v.cast<std::string>();
    else if (k == "integrator") a.integrator = v.cast<std::string>();
    else if (k == "precision") a.precision = v.cast<std::string>();
    else if (k == "early_termination") a.early_termination = scene_number("--early-termination");
    else if (k == "max_list_length") a.max_list_length = int64_t(scene_number("--max-list-length"));
    else if (k == "tile_size") a.tile_size = uint32_t(scene_number("--tile-size"));
    else if (k == "scalar") a.opt.scalar = v.cast<std::string>();
    else if (k == "association") a.association = v.cast<std::string>();
    else if (k == "q") a.opt.q_path = v.cast<std::string>();
    else if (k == "model") a.molecule.model = model_number(v);
    else if (k == "waters") a.molecule.no_waters = !flag(v, k);
    else if (k == "hydrogens") a.molecule.no_hydrogens = !flag(v, k);
    else if (k == "no_culling") out.no_culling = v.cast<bool>();
    else if (k == "frames") out.frames = int(number(whole_range(1, 100000)));
    else throw py::type_error("render() got an unexpected option '" + k + "'");
  }
  if (out.no_culling) a.also_given.push_back("--no-culling");
  return out;
}

// The scene of a call: JSON text (or, when empty, `name` as a bare file or
// the default scene) with its data and options applied; loaded without the GIL.
std::unique_ptr<SceneInput> load(const std::string& text, const std::string& name, const std::string& base_dir,
                                 const py::dict& data, Options& o) {
  const SceneData sd = scene_data_from(data);
  auto in = std::make_unique<SceneInput>();
  run_cancellable([&](const std::atomic<bool>&) {
    // No JSON text: `name` is a bare mesh, sphere or surface file, or empty
    // for the embedded default scene, as on the command line.
    if (text.empty()) o.args.input = name;  // a bare file, as `zsweep render FILE`
    o.args.check_before_load();
    *in = text.empty() ? load_scene_input(name, o.args.read_options(), o.args.molecule)
                       : load_scene_input_text(text, name, base_dir, sd, o.args.molecule);
    o.args.apply(*in, name.empty() ? "the default scene" : name);
  });
  return in;
}

std::vector<std::string> names_of(const SceneJob& job) {
  std::vector<std::string> names = job.channel_names();
  if (names.empty()) names = job.grid().channels == 5 ? std::vector<std::string>{"R", "G", "B", "A", "Z"}
                                                      : std::vector<std::string>{"R", "G", "B", "A"};
  return names;
}

py::tuple render_job(SceneJob& job, const Options& o);

// A loaded scene rendered through its SceneJob into a new array.
py::tuple render_input(SceneInput& in, const Options& o) {
  std::unique_ptr<SceneJob> job;
  run_cancellable([&](const std::atomic<bool>&) {
    in.scene.settings.face_area_stats = true;  // the stats are always returned
    job = make_scene_job(in, o.no_culling);
    job->check_budget(0);
  });
  return render_job(*job, o);
}

// One render of a job's frames into a new array.
py::tuple render_job(SceneJob& job_ref, const Options& o) {
  SceneJob* job = &job_ref;
  const TileGrid g = job->grid();
  py::array_t<float> img({size_t(g.height), size_t(g.width), size_t(g.channels)});
  float* px = img.mutable_data();
  FrameReport report;
  std::unique_ptr<TiledRenderer> r;
  const uint64_t out_bytes = uint64_t(g.width) * g.height * g.channels * sizeof(float);
  run_cancellable([&](const std::atomic<bool>& cancel) {
    ArraySink sink(px, g, cancel);
    struct Warmup : TileSink {  // frames before the last: nowhere, but Ctrl-C still stops them
      const std::atomic<bool>& cancel;
      explicit Warmup(const std::atomic<bool>& c) : cancel(c) {}
      void tile(const TileRect&, const float*) override {
        if (cancel) throw Cancelled();
      }
    } warmup(cancel);
    r = render_frames(*job, o.frames, sink, out_bytes, false, &report.frame_ms, &warmup);
  });
  if (o.frames > 1) report.best_ms = *std::min_element(report.frame_ms.begin(), report.frame_ms.end());
  return py::make_tuple(img, names_of(*job), job->stats(*r, report).dump());
}

// render(scene_json, name, base_dir, data, options) -> (image, channel names, stats JSON)
py::tuple render(const std::string& text, const std::string& name, const std::string& base_dir, const py::dict& data,
                 const py::dict& options) {
  Options o = options_from(options);
  std::unique_ptr<SceneInput> in = load(text, name, base_dir, data, o);
  return render_input(*in, o);
}

// A scene loaded once and rendered many times (zsweep.Renderer): the mesh
// and what its renderer keeps between views (a volume's topology) are built
// once; a new camera replaces the scene's for the following renders.
class Session {
 public:
  Session(const std::string& text, const std::string& name, const std::string& base_dir, const py::dict& data,
          const py::dict& options)
      : o_(options_from(options)), in_(load(text, name, base_dir, data, o_)) {
    run_cancellable([&](const std::atomic<bool>&) {
      in_->scene.settings.face_area_stats = true;  // the stats are always returned
      job_ = make_scene_job(*in_, o_.no_culling);
      job_->check_budget(0);
    });
  }

  // render(camera_json) -> (image, channel names, stats JSON); "" keeps the camera.
  py::tuple render(const std::string& camera_json) {
    if (!camera_json.empty()) {
      Camera cam = in_->scene.settings.camera;
      parse_camera_json(camera_json, "camera", &cam);
      run_cancellable([&](const std::atomic<bool>&) {
        in_->scene.settings.camera = cam;
        if (!job_->set_camera(cam)) {
          job_.reset();
          job_ = make_scene_job(*in_, o_.no_culling);
          job_->check_budget(0);
        }
      });
    }
    return render_job(*job_, o_);
  }

 private:
  Options o_;
  std::unique_ptr<SceneInput> in_;
  std::unique_ptr<SceneJob> job_;
};

// reference(...) -> the same triple, from the independent ray casters
// (surface scenes: the renderer's exact mode). Not interruptible inside.
py::tuple reference(const std::string& text, const std::string& name, const std::string& base_dir,
                    const py::dict& data, const py::dict& options, uint32_t ao_samples) {
  Options o = options_from(options);
  if (ao_samples) o.args.also_given.push_back("--ao-samples");
  std::unique_ptr<SceneInput> in = load(text, name, base_dir, data, o);
  if (ao_samples && !in->scene.spheres.ao.directions)
    throw py::value_error("ao_samples needs a sphere scene with an 'ao' block");
  if (in->scene.kind == SceneKind::Surfaces) {
    in->scene.surfaces.shadows.mode = ShadowMode::Exact;
    return render_input(*in, o);
  }
  ReferenceImage ref;
  run_cancellable([&](const std::atomic<bool>&) { ref = reference_image(*in, ao_samples); });
  const size_t C = ref.names.size();
  py::array_t<float> img({size_t(ref.height), size_t(ref.width), C});
  std::copy(ref.pixels.begin(), ref.pixels.end(), img.mutable_data());
  return py::make_tuple(img, ref.names, ref.stats.dump());
}

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

// An (height, width, 4+) array's RGBA as an Image; `which` names it in the error.
Image image_of(const FloatArray& x, const std::string& which) {
  if (x.ndim() != 3 || x.shape(2) < 4) throw py::value_error(which + " must have shape (height, width, 4) or more channels");
  Image img(uint32_t(x.shape(1)), uint32_t(x.shape(0)));
  const size_t C = size_t(x.shape(2)), n = size_t(x.shape(0)) * size_t(x.shape(1));
  for (size_t p = 0; p < n; ++p) std::copy_n(x.data() + p * C, 4, img.rgba.data() + p * 4);
  return img;
}

// write_image(path, rgba): PNG (8-bit), EXR or TIFF (float) by the name, as
// the command line writes RGBA; nothing under `path` if it fails.
void write(const std::string& path, const FloatArray& x) {
  const Image img = image_of(x, "image");
  py::gil_scoped_release nogil;
  write_image(path, img);
}

py::dict compare(const FloatArray& a, const FloatArray& b, bool rgb) {
  if (a.ndim() == 3 && b.ndim() == 3 && (a.shape(0) != b.shape(0) || a.shape(1) != b.shape(1)))
    throw py::value_error("the images' sizes differ");
  const ImageDiff d = compare_images(image_of(a, "a"), image_of(b, "b"), rgb ? 3 : 4);
  py::dict out;
  out["max_abs"] = d.max_abs;
  out["rmse"] = d.rmse;
  out["psnr"] = std::isinf(d.psnr) ? py::object(py::none()) : py::object(py::float_(d.psnr));
  out["pixels_over_1_255"] = d.pixels_over_1_255;
  out["worst_pixel"] = py::make_tuple(d.worst_x, d.worst_y);
  return out;
}

}  // namespace

}  // namespace zs::python

PYBIND11_MODULE(_zsweep, m) {
  m.doc() = "zsweep's renderers (use the zsweep package, not this module)";
  m.def("render", &zs::python::render, py::arg("scene_json"), py::arg("name"), py::arg("base_dir"), py::arg("data"),
        py::arg("options"));
  m.def("reference", &zs::python::reference, py::arg("scene_json"), py::arg("name"), py::arg("base_dir"),
        py::arg("data"), py::arg("options"), py::arg("ao_samples"));
  m.def("write_image", &zs::python::write, py::arg("path"), py::arg("image"));
  py::class_<zs::python::Session>(m, "Session")
      .def(py::init<const std::string&, const std::string&, const std::string&, const py::dict&, const py::dict&>(),
           py::arg("scene_json"), py::arg("name"), py::arg("base_dir"), py::arg("data"), py::arg("options"))
      .def("render", &zs::python::Session::render, py::arg("camera_json"));
  m.def("compare", &zs::python::compare, py::arg("a"), py::arg("b"), py::arg("rgb") = false);
  zs::python::add_generate(m);
  // An option that does not apply to the input, or a bad option value.
  py::register_exception<zs::UsageError>(m, "UsageError", PyExc_ValueError);
}
