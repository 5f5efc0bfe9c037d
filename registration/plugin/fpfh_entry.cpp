// The entry points of the plugin conform_fpfh (coarse_fpfh.cpp and PCL's features behind it), called through
// registration/src/fpfh_plugin.cpp. C names, so that dlsym finds them; C++ types, as both sides are conform.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/registration/coarse_fpfh.h"

#define CONFORM_PLUGIN_EXPORT extern "C" __attribute__((visibility("default")))

CONFORM_PLUGIN_EXPORT bool conform_fpfh_options_valid(const conform::FpfhOptions& options, std::string* error) {
  return options.IsValid(error);
}

CONFORM_PLUGIN_EXPORT void conform_fpfh_ransac(const std::vector<Eigen::Vector3d>& scan,
                                               const std::vector<Eigen::Vector3d>& reference,
                                               const conform::FpfhOptions& options, conform::FpfhResult* result) {
  *result = conform::fpfh_ransac(scan, reference, options);
}
