// The module's pictures: write_film_strip (`shellspace render`).
#include <string>

#include "python/array_arguments.h"
#include "python/module_common.h"
#include "python/parameter_docs.h"
#include "shellspace/io/output_paths.h"
#include "shellspace/render/film_strip.h"

namespace shellspace {
namespace pymodule {
namespace {

// `shellspace render` on frames in memory: the same options, the same file.
void WriteFilmStripPy(const std::string& path, const py::object& frames_object,
                      const py::object& F, int width, int height,
                      const std::string& view, const std::string& up,
                      bool labels, const std::string& color,
                      const std::string& shading) {
  if (path.empty()) throw InputError("path: an empty path");
  OutputPaths().OutputPng("path", path).Check();  // named .png, writable
  RenderOptions options;
  options.width = width;
  options.height = height;
  options.view = ParseView(view);
  options.up = ParseUpAxis(up);
  options.labels = labels;
  options.color = ParseSurfaceColor(color);
  options.shading = ParseShading(shading);
  const Frames frames = FramesArgument(frames_object, F);
  CheckFilmStripMemory(static_cast<int>(frames.shapes.size()), options,
                       "write_film_strip");
  WriteFilmStrip(frames.shapes, frames.faces, options, path);
}

}  // namespace

void RegisterRender(py::module_& m) {
  m.def("write_film_strip", &WriteFilmStripPy, py::arg("path"),
        py::arg("frames"), py::arg("F"), py::arg("width") = 0,
        py::arg("height") = 0, py::arg("view") = "front",
        py::arg("up") = "auto", py::arg("labels") = true,
        py::arg("color") = "plain", py::arg("shading") = "gouraud",
        WithParameters(
            "write_film_strip",
            "Writes frames as a PNG film strip, as `shellspace render` does: "
            "width the whole image (0: 320 per column), height per frame (0: "
            "square), up auto|x|y|z|-x|-y|-z, labels under the frames, color "
            "plain|displacement. A strip beyond the CLI's bounds (a frame "
            "wider or higher than 8192 pixels; an estimated memory of 6 B x "
            "width x height + 128 B x frame pixels above half the physical "
            "memory) is an InputError before anything is drawn.")
            .c_str());
}

}  // namespace pymodule
}  // namespace shellspace
