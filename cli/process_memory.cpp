#include "cli/process_memory.hpp"

#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string>

// <cstdlib> has brought in the C library's <features.h>, which defines __GLIBC__.
#if defined(__GLIBC__)
#include <malloc.h>
#include <unistd.h>
#endif

namespace daylit::cli {

namespace {

// Set for the second start, so that there is never a third (glibc drops GLIBC_TUNABLES for
// set-user-ID programs, where the tunable alone would not show that the first has been).
constexpr const char* kStartedAgain = "DAYLIT_HUGE_PAGES_ASKED";

bool kernel_waits_for_advice() {
  std::ifstream mode("/sys/kernel/mm/transparent_hugepage/enabled");
  std::string line;
  return std::getline(mode, line) && line.find("[madvise]") != std::string::npos;
}

}  // namespace

void use_transparent_huge_pages(char** argv) {
#if defined(__GLIBC__) && defined(__linux__) && !defined(__SANITIZE_ADDRESS__)
  if (std::getenv(kStartedAgain) != nullptr) return;
  const char* tunables = std::getenv("GLIBC_TUNABLES");
  if (tunables != nullptr && std::strstr(tunables, "glibc.malloc.hugetlb") != nullptr) return;
  const char* preload = std::getenv("LD_PRELOAD");
  if ((preload != nullptr && *preload != '\0') || !kernel_waits_for_advice()) return;
  const std::string before = tunables != nullptr ? tunables : "";
  const std::string asked = before.empty() ? "glibc.malloc.hugetlb=1" : before + ":glibc.malloc.hugetlb=1";
  if (setenv("GLIBC_TUNABLES", asked.c_str(), 1) != 0 || setenv(kStartedAgain, "1", 1) != 0) return;
  execv("/proc/self/exe", argv);
  // Still here: the program could not be run again; on as it is, with the environment as it was.
  if (tunables != nullptr)
    setenv("GLIBC_TUNABLES", before.c_str(), 1);
  else
    unsetenv("GLIBC_TUNABLES");
  unsetenv(kStartedAgain);
#else
  (void)argv;
#endif
}

void keep_freed_memory() {
#if defined(__GLIBC__)
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
#endif
}

}  // namespace daylit::cli
