// fpfh_ransac and FpfhOptions::IsValid of coarse_fpfh.h, forwarded to the plugin conform_fpfh, where coarse_fpfh.cpp
// is built with PCL's features library: loading that at every start cost `conform --help` most of its 0.05 s
// (116k relocations bound by the loader), for a feature only `--init fpfh` uses.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "conform/core/plugin.h"
#include "conform/registration/coarse_fpfh.h"

namespace conform {

namespace {

constexpr const char* kPlugin = "conform_fpfh";

}  // namespace

bool FpfhOptions::IsValid(std::string* error) const {
  using Fn = bool(const FpfhOptions&, std::string*);
  return Plugin::load(kPlugin).symbol<Fn>("conform_fpfh_options_valid")(*this, error);
}

FpfhResult fpfh_ransac(const std::vector<Eigen::Vector3d>& scan, const std::vector<Eigen::Vector3d>& reference,
                       const FpfhOptions& options) {
  using Fn = void(const std::vector<Eigen::Vector3d>&, const std::vector<Eigen::Vector3d>&, const FpfhOptions&,
                  FpfhResult*);
  FpfhResult result;
  Plugin::load(kPlugin).symbol<Fn>("conform_fpfh_ransac")(scan, reference, options, &result);
  return result;
}

}  // namespace conform
