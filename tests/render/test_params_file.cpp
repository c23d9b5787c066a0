// Parameter files: a JSON object of names and values read as assignments in file order; a bad
// file is an error naming it.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "bounce/core/error.h"
#include "bounce/render/params.h"
#include "bounce/render/params_file.h"

namespace bounce {
namespace {

std::string write_file(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path.string();
}

TEST(ParamsFile, ReadsNamesAndValuesInOrder) {
  const std::string path = write_file("bounce_params_ok.json",
                                      R"({"k": 50, "radius": 0.25, "slice": true, "mode": "2"})");
  const std::vector<std::string> a = read_params_file(path);
  ASSERT_EQ(a.size(), 4u);
  EXPECT_EQ(a[0], "k=50");
  EXPECT_EQ(a[1], "radius=0.25");
  EXPECT_EQ(a[2], "slice=true");
  EXPECT_EQ(a[3], "mode=2");
  int k = 0, mode = 0;
  float radius = 0.0f;
  bool slice = false;
  ParamSet set;
  set.add_int("k", &k, 1, 100, "");
  set.add_float("radius", &radius, 0.0, 1.0, "");
  set.add_bool("slice", &slice, "");
  set.add_int("mode", &mode, 0, 3, "");
  for (const auto& assignment : a) set.set_assignment(assignment);
  EXPECT_EQ(k, 50);
  EXPECT_FLOAT_EQ(radius, 0.25f);
  EXPECT_TRUE(slice);
  EXPECT_EQ(mode, 2);
}

TEST(ParamsFile, BadFilesAreErrorsNamingTheFile) {
  const auto message = [](const std::string& path) {
    try {
      read_params_file(path);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string missing = "/nonexistent/bounce_params.json";
  EXPECT_NE(message(missing).find(missing), std::string::npos);
  const std::string bad_json = write_file("bounce_params_bad.json", "{\"k\": ");
  EXPECT_NE(message(bad_json).find("not valid JSON"), std::string::npos);
  const std::string not_object = write_file("bounce_params_list.json", "[1, 2]");
  EXPECT_NE(message(not_object).find("JSON object"), std::string::npos);
  const std::string nested = write_file("bounce_params_nested.json", R"({"k": [1]})");
  EXPECT_NE(message(nested).find("'k'"), std::string::npos);
}

}  // namespace
}  // namespace bounce
