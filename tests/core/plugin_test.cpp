// Plugin::load (core/plugin.h): modules opened on first use, found in the build tree, named in every error.

#include "conform/core/plugin.h"

#include <string>

#include <gtest/gtest.h>

#include "conform/core/error.h"

namespace conform {
namespace {

// The CAD module (cad/CMakeLists.txt, conform_add_plugin) is built before every test (conform_add_tests).
constexpr const char* kCad = "conform_cad";

TEST(Plugin, OpensAModuleOnceAndFindsItsFunctions) {
  const Plugin& first = Plugin::load(kCad);
  const Plugin& again = Plugin::load(kCad);
  EXPECT_EQ(&first, &again);
  EXPECT_NE(first.path().find("libconform_cad.so"), std::string::npos) << first.path();
  using Fn = void(const std::string&);
  EXPECT_NE(first.symbol<Fn>("conform_cad_read"), nullptr);
}

TEST(Plugin, AMissingModuleNamesTheFileAndWhereItLooked) {
  try {
    Plugin::load("conform_no_such_plugin");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("libconform_no_such_plugin.so"), std::string::npos) << message;
    EXPECT_NE(message.find(std::string(CONFORM_TEST_BUILD_DIR) + "/libconform_no_such_plugin.so"), std::string::npos)
        << message;
  }
}

TEST(Plugin, AMissingSymbolNamesTheModuleAndTheSymbol) {
  const Plugin& plugin = Plugin::load(kCad);
  try {
    plugin.symbol<void()>("conform_no_such_symbol");
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(plugin.path()), std::string::npos) << message;
    EXPECT_NE(message.find("conform_no_such_symbol"), std::string::npos) << message;
  }
}

}  // namespace
}  // namespace conform
