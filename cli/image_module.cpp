// Loads the image writer module (report_image.cpp) on first use, from beside the executable.

#include <dlfcn.h>

#include <filesystem>

#include "cli/reports.hpp"
#include "geometry/error.hpp"

namespace daylit::cli {

namespace {

using WriteImage = bool (*)(const char*, const GridReport*, char*, std::size_t);

WriteImage load_image_writer() {
  static WriteImage writer = [] {
    const std::filesystem::path module =
        std::filesystem::read_symlink("/proc/self/exe").parent_path() / "libdaylit_image_writer.so";
    void* handle = ::dlopen(module.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) throw Error(std::string("cannot load the image writer: ") + ::dlerror());
    auto* entry = reinterpret_cast<WriteImage>(::dlsym(handle, "daylit_write_falsecolour_image"));
    if (!entry) throw Error(module.string() + ": no daylit_write_falsecolour_image");
    return entry;
  }();
  return writer;
}

}  // namespace

void write_falsecolour_image(const std::string& path, const GridReport& report) {
  char error[1024] = "";
  if (!load_image_writer()(path.c_str(), &report, error, sizeof error)) throw Error(error);
}

}  // namespace daylit::cli
