#include "python/src/usage_guard.h"

#include <mutex>
#include <stdexcept>
#include <string>
#include <unordered_set>

namespace ccma::python {
namespace {

// The objects some thread is inside a method of. Guarded by InUseMutex().
std::unordered_set<const void*>& InUse() {
  static std::unordered_set<const void*> in_use;
  return in_use;
}

std::mutex& InUseMutex() {
  static std::mutex mutex;
  return mutex;
}

}  // namespace

UsageGuard::UsageGuard(const void* key, const char* class_name) : key_(key) {
  const std::lock_guard<std::mutex> lock(InUseMutex());
  if (!InUse().insert(key).second) {
    throw std::runtime_error(std::string(class_name) +
                             " is being used by another thread; use one problem per thread");
  }
}

UsageGuard::~UsageGuard() {
  const std::lock_guard<std::mutex> lock(InUseMutex());
  InUse().erase(key_);
}

}  // namespace ccma::python
