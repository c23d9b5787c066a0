// A signal that arrives while an image is written leaves the old file and no temporary file.
#include <gtest/gtest.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "bounce/core/image.h"
#include "bounce/core/image_io.h"
#include "bounce/core/interrupt.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

TEST(Interrupt, SaveLeavesTheOldFileAndNoTemporary) {
  const fs::path dir = fs::temp_directory_path() / "bounce-interrupt-save";
  fs::remove_all(dir);
  fs::create_directories(dir);
  const fs::path out = dir / "image.pfm";
  std::ofstream(out) << "old";
  set_interrupt_signal(SIGTERM);
  try {
    save_image(out.string(), Image(4, 4, vec3(1.0f)));
    ADD_FAILURE() << "the save did not stop";
  } catch (const Interrupted& e) {
    EXPECT_EQ(e.signal(), SIGTERM);
    EXPECT_STREQ(e.what(), "interrupted by SIGTERM: stopped before writing any output");
  }
  set_interrupt_signal(0);
  std::ifstream in(out);
  std::stringstream text;
  text << in.rdbuf();
  EXPECT_EQ(text.str(), "old");
  size_t files = 0;
  for ([[maybe_unused]] const auto& entry : fs::directory_iterator(dir)) ++files;
  EXPECT_EQ(files, 1u);
  // With no signal the same save goes through.
  save_image(out.string(), Image(4, 4, vec3(1.0f)));
  EXPECT_EQ(load_image(out.string()).width(), 4);
  fs::remove_all(dir);
}

TEST(Interrupt, ThrowsOnlyAfterASignal) {
  set_interrupt_signal(0);
  EXPECT_NO_THROW(throw_if_interrupted());
  set_interrupt_signal(SIGINT);
  EXPECT_THROW(throw_if_interrupted(), Interrupted);
  set_interrupt_signal(0);
}

}  // namespace
}  // namespace bounce
