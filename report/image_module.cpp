// Loads the image writer module (report_image.cpp, report_plot.cpp) on first use, from beside the
// executable.

#include <dlfcn.h>

#include <filesystem>

#include "report/plot.hpp"
#include "report/reports.hpp"
#include "geometry/error.hpp"

namespace daylit::cli {

namespace {

using WriteImage = bool (*)(const char*, const GridReport*, char*, std::size_t);
using WritePlot = bool (*)(const char*, const Plot*, char*, std::size_t);

const std::filesystem::path& module_path() {
  static const std::filesystem::path module =
      std::filesystem::read_symlink("/proc/self/exe").parent_path() / "libdaylit_image_writer.so";
  return module;
}

// The module's entry point `name`, loading the module on first use.
void* module_entry(const char* name) {
  static void* handle = [] {
    void* h = ::dlopen(module_path().c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!h) throw Error(std::string("cannot load the image writer: ") + ::dlerror());
    return h;
  }();
  void* entry = ::dlsym(handle, name);
  if (!entry) throw Error(module_path().string() + ": no " + name);
  return entry;
}

WriteImage load_image_writer() {
  static WriteImage writer = reinterpret_cast<WriteImage>(module_entry("daylit_write_falsecolour_image"));
  return writer;
}

WritePlot load_plot_writer() {
  static WritePlot writer = reinterpret_cast<WritePlot>(module_entry("daylit_write_loglog_plot"));
  return writer;
}

}  // namespace

void write_falsecolour_image(const std::string& path, const GridReport& report) {
  char error[1024] = "";
  if (!load_image_writer()(path.c_str(), &report, error, sizeof error)) throw Error(error);
}

void write_loglog_plot(const std::string& path, const Plot& plot) {
  char error[1024] = "";
  if (!load_plot_writer()(path.c_str(), &plot, error, sizeof error)) throw Error(error);
}

}  // namespace daylit::cli
