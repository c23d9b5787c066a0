// Inputs written as a hostile user would (issue 14): each must end in a clear error with the
// usual prefix and status 1, never a crash, a hang, a silent default or a late failure.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>

#include "app/cli_test_util.h"

namespace bounce {
namespace {

namespace fs = std::filesystem;

using cli_test::Result;
using cli_test::run;
using cli_test::scratch_dir;

void write(const fs::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

std::string read(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

// An error of ours: status 1 and the message after the usual prefix.
void expect_error(const std::string& args, const std::string& message) {
  const Result r = run(args);
  EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
  EXPECT_NE(r.output.find("bounce: error:"), std::string::npos) << args << "\n" << r.output;
  EXPECT_NE(r.output.find(message), std::string::npos) << args << "\n" << r.output;
}

// A small triangle with an emissive material, and the OBJ's MTL beside it.
void write_emitter_obj(const fs::path& dir, const std::string& x) {
  write(dir / "lamp.mtl", "newmtl lamp\nKd 0 0 0\nKe 10 10 10\n");
  write(dir / "lamp.obj",
        "mtllib lamp.mtl\nv " + x + " 0 0\nv " + x + " 1 0\nv 0 0 1\nusemtl lamp\nf 1 2 3\n");
}

TEST(CliReliability, HugeCoordinatesAreRefusedNotPassedToTheTracer) {
  const fs::path dir = scratch_dir("huge");
  write(dir / "far.bounce.json",
        R"({"models": [{"builtin": "cornell"}],
            "lights": [{"type": "point", "position": [2e18, 0, 0], "intensity": [1, 1, 1]}]})");
  for (const char* command : {"info",
                              "render -W 8 -H 8 -o "
                              "x.png"})
    expect_error(std::string(command) + " " + (dir / "far.bounce.json").string(),
                 "point) position (2e+18, 0, 0) is outside the scene extent (|coordinate| <= "
                 "1e+06 m)");

  write_emitter_obj(dir, "2e18");
  expect_error("info " + (dir / "lamp.obj").string(),
               "mesh 'shape0' vertex 0 (2e+18, 0, 0) is outside the scene extent");

  // A KHR_lights_punctual light on a node placed at x = 3e18.
  write(dir / "light.gltf", R"({"asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "intensity": 5}]}},
    "scene": 0, "scenes": [{"nodes": [0]}],
    "nodes": [{"translation": [3e18, 0, 0], "extensions": {"KHR_lights_punctual": {"light": 0}}}]})");
  expect_error("info " + (dir / "light.gltf").string(), "is outside the scene extent");
}

TEST(CliReliability, AnimationKeysMustBeFiniteAndWithinTheExtent) {
  const fs::path dir = scratch_dir("keys");
  write(dir / "keys.bounce.json",
        R"({"models": [{"builtin": "cornell"}],
            "lights": [{"type": "point", "position": [0.2, 0.4, 0.2], "intensity": [1, 1, 1],
                        "animation": {"keys": [{"time": 0, "position": [0.2, 0.4, 0.2]},
                                               {"time": 1, "position": [1e308, 0.4, 0.2]}]}}]})");
  expect_error("info " + (dir / "keys.bounce.json").string(),
               "key 1 (at 1 s) has a value that is not finite or is outside the scene extent");
}

TEST(CliReliability, NonFiniteNumbersAreRefused) {
  // NaN passes a range check; our own check names it. Infinity fails either check first.
  const std::pair<const char*, const char*> cases[] = {
      {"render -W 8 -H 8 --at nan", "--at: 'nan' is not a finite number"},
      {"bench cornell -W 8 -H 8 --at nan", "--at: 'nan' is not a finite number"},
      {"render -W 8 -H 8 --exposure nan", "--exposure: 'nan' is not a finite number"},
      {"render -W 8 -H 8 --exposure inf", "--exposure"},
      {"render -W 8 -H 8 --exposure -1e999", "--exposure"},
      {"render -W 8 -H 8 --exposure 1000", "--exposure"},
      {"reference -W 8 -H 8 --exposure nan", "--exposure: 'nan' is not a finite number"},
      {"reference -W 8 -H 8 --time nan", "--time: 'nan' is not a finite number"},
      {"sequence -W 8 -H 8 --fps nan --to 1", "--fps: 'nan' is not a finite number"},
      {"sequence -W 8 -H 8 --fps inf --to 1", "--fps: 'inf' is not a finite number"},
      {"bench cornell --settle-tolerance nan", "--settle-tolerance: 'nan' is not a finite number"},
      {"compare a.exr b.exr --heatmap-max inf", "--heatmap-max"},
      {"render -W 8 -H 8 --radius nan", "--radius: 'nan' is not a finite number"},
  };
  for (const auto& [args, message] : cases) expect_error(args, message);
}

TEST(CliReliability, ParserErrorsUseThePrefixAndStatusOne) {
  for (const char* args : {"render --width abc", "render --no-such-option", "frobnicate", ""}) {
    const Result r = run(args);
    EXPECT_EQ(r.status, 1) << args << "\n" << r.output;
    EXPECT_EQ(r.output.rfind("bounce: error: ", 0), 0u) << args << "\n" << r.output;
  }
  EXPECT_EQ(run("render --help").status, 0);
}

TEST(CliReliability, OutputIsCheckedBeforeRendering) {
  const fs::path dir = scratch_dir("outputs");
  for (const char* command : {"render", "reference", "sequence --to 0.1"})
    expect_error(std::string(command) + " -W 8 -H 8 -o ''", "--out: the file name is empty");
  expect_error("bench cornell --json ''", "--json: the file name is empty");
  expect_error("compare a.exr b.exr --heatmap ''", "--heatmap: the file name is empty");
  // Both fail before the scene is loaded: nothing of a render is printed.
  for (const std::string& out : {std::string("/proc/x.png"), (dir / "x.jpg").string()}) {
    for (const char* command : {"render", "reference"}) {
      const Result r = run(std::string(command) + " -W 8 -H 8 -o " + out);
      EXPECT_EQ(r.status, 1) << r.output;
      EXPECT_NE(r.output.find("bounce: error: cannot write " + out), std::string::npos) << r.output;
      EXPECT_EQ(r.output.find("triangles"), std::string::npos) << "rendered first:\n" << r.output;
    }
  }
  EXPECT_NE(run("render -W 8 -H 8 -o " + (dir / "x.jpg").string())
                .output.find("unsupported file extension '.jpg'"),
            std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "x.jpg"));
}

// Photons held across frames count too: settings whose photons cannot fit are refused before any
// is traced, small images or not.
TEST(CliReliability, PhotonSettingsThatCannotFitAreRefused) {
  for (const char* command : {"render", "bench cornell", "sequence cornell --to 1"}) {
    expect_error(std::string(command) + " -W 64 -H 64 --photons 10000000 --param history_passes=64",
                 "photons and technique data");
    expect_error(std::string(command) +
                     " -W 64 -H 64 -t vertex --param diffuse_reflections=1024 "
                     "--param recursion_depth=4",
                 "use a smaller image or fewer photons");
  }
  // The defaults and a large but plausible setting fit.
  const fs::path dir = scratch_dir("photon-memory");
  const Result ok =
      run("render -W 32 -H 32 --spp 1 --photons 200000 -o " + (dir / "x.png").string());
  EXPECT_EQ(ok.status, 0) << ok.output;
}

TEST(CliReliability, MemoryEstimateIsCheckedAgainstTheCap) {
  // 480 bytes per pixel for frames, 48 for reference's sums: 2^28 pixels make 120 and 12 GiB.
  for (const char* command : {"render", "bench cornell", "sequence cornell --to 1"})
    expect_error(std::string(command) + " -W 16384 -H 16384",
                 "(image 120.0, geometry 0.0, textures 0.0, photons and technique data 0.");
  expect_error("reference -W 16384 -H 16384",
               "at 16384x16384 needs about 12.0 GiB (image 12.0, geometry 0.0");
  expect_error("reference -W 16384 -H 16384", "more than the cap of 8.0 GiB");
  expect_error("render -W 16384 -H 16384", "BOUNCE_MEMORY_LIMIT_GB");
  // The cap follows the environment variable.
  ASSERT_EQ(::setenv("BOUNCE_MEMORY_LIMIT_GB", "0.001", 1), 0);
  const Result r = run("render -W 64 -H 64 --spp 1 -o x.png");
  ASSERT_EQ(::setenv("BOUNCE_MEMORY_LIMIT_GB", "lots", 1), 0);
  const Result bad = run("render -W 8 -H 8 -o x.png");
  ::unsetenv("BOUNCE_MEMORY_LIMIT_GB");
  EXPECT_EQ(r.status, 1) << r.output;
  EXPECT_NE(r.output.find("at 64x64 needs about 0."), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("more than the cap of 0.0 GiB"), std::string::npos) << r.output;
  EXPECT_EQ(bad.status, 1) << bad.output;
  EXPECT_NE(bad.output.find("BOUNCE_MEMORY_LIMIT_GB='lots' is not a positive number of GiB"),
            std::string::npos)
      << bad.output;
}

TEST(CliReliability, ObjIndicesDoNotWrapAround) {
  const fs::path dir = scratch_dir("obj-index");
  for (const char* index : {"4294967295", "4294967300", "-4294967297"}) {
    write(dir / "wrap.obj",
          std::string("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nv 1 1 1\nf 1 2 ") + index + "\n");
    expect_error("info " + (dir / "wrap.obj").string(),
                 (dir / "wrap.obj").string() + ":6: face vertex '" + index + "': index " + index +
                     " is out of range");
  }
}

TEST(CliReliability, DevicesAndFifosAreRefusedAsInputs) {
  const fs::path dir = scratch_dir("devices");
  write(dir / "zero.obj", "mtllib /dev/zero\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expect_error("info " + (dir / "zero.obj").string(),
               "mtllib '/dev/zero': /dev/zero is not a regular file");
  fs::create_symlink("/dev/zero", dir / "device.obj");
  expect_error("info " + (dir / "device.obj").string(), "OBJ file is a device, not a regular file");
  fs::create_symlink("/dev/zero", dir / "device.gltf");
  expect_error("info " + (dir / "device.gltf").string(), "glTF file is a device");
  // A glTF buffer that is a fifo: opening it would block for ever.
  ASSERT_EQ(::mkfifo((dir / "pipe.bin").c_str(), 0600), 0);
  write(dir / "pipe.gltf", R"({"asset": {"version": "2.0"},
    "buffers": [{"uri": "pipe.bin", "byteLength": 36}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})");
  expect_error("info " + (dir / "pipe.gltf").string(), "pipe.bin' is not a regular file");
  ASSERT_EQ(::mkfifo((dir / "pipe.bounce.json").c_str(), 0600), 0);
  expect_error("info " + (dir / "pipe.bounce.json").string(), "scene file is a fifo");
}

TEST(CliReliability, Utf16ObjIsNamedAsSuch) {
  const fs::path dir = scratch_dir("utf16");
  const std::string ascii = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
  std::string utf16 = "\xFF\xFE";
  for (char c : ascii) utf16 += std::string{c, '\0'};
  write(dir / "wide.obj", utf16);
  expect_error("info " + (dir / "wide.obj").string(), "the file is UTF-16 text");
  write(dir / "nobom.obj", utf16.substr(2));
  expect_error("info " + (dir / "nobom.obj").string(), "not a text OBJ: byte 1 is a NUL character");
}

TEST(CliReliability, GltfVersionsAndRequiredExtensionsAreNamed) {
  const fs::path dir = scratch_dir("gltf-messages");
  write(dir / "old.gltf", R"({"asset": {"version": "1.0"}, "meshes": {"m": {"primitives": []}}})");
  expect_error("info " + (dir / "old.gltf").string(), "this is a glTF 1.0 file");
  write(dir / "older.gltf", R"({"meshes": {"m": {"primitives": []}}, "scene": "s"})");
  expect_error("info " + (dir / "older.gltf").string(), "looks like a glTF 1.0 file");
  // Binary glTF 1.0: magic, version 1, length, content length, content format 0 (JSON).
  const std::string json = R"({"meshes": {}})";
  std::string glb = "glTF";
  for (uint32_t word : {1u, uint32_t(20 + json.size()), uint32_t(json.size()), 0u})
    glb.append(reinterpret_cast<const char*>(&word), 4);
  write(dir / "old.glb", glb + json);
  expect_error("info " + (dir / "old.glb").string(), "this is a binary glTF 1.0 file");
  write(dir / "draco.gltf", R"({"asset": {"version": "2.0"},
    "extensionsUsed": ["KHR_draco_mesh_compression"],
    "extensionsRequired": ["KHR_draco_mesh_compression"],
    "accessors": [{"componentType": 5126, "count": 3, "type": "VEC3"}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})");
  expect_error("info " + (dir / "draco.gltf").string(),
               "requires glTF extension(s) KHR_draco_mesh_compression which bounce does not "
               "support");
}

// A triangle as a data URI: three float positions (0,0,0), (1,0,0), (0,1,0), 36 bytes.
constexpr const char* kTriangleBuffer =
    R"({"uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA", "byteLength": 36})";

TEST(CliReliability, WronglyTypedGltfValuesAreReported) {
  const fs::path dir = scratch_dir("gltf-types");
  write(dir / "typed.gltf", std::string(R"({"asset": {"version": "2.0"},
    "buffers": [)") + kTriangleBuffer +
                                R"(],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": -1},
                                            "roughnessFactor": "0.5"}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}]})");
  const Result r = run("info " + (dir / "typed.gltf").string());
  EXPECT_EQ(r.status, 0) << r.output;
  EXPECT_NE(r.output.find("/materials/0/pbrMetallicRoughness/baseColorTexture/index should be an "
                          "integer >= 0, found -1"),
            std::string::npos)
      << r.output;
  EXPECT_NE(r.output.find("/materials/0/pbrMetallicRoughness/roughnessFactor should be a number, "
                          "found \"0.5\""),
            std::string::npos)
      << r.output;
}

// Starts bounce with `args` (stdout and stderr to `log`), waits until it has installed its
// signal handlers (and, when given, until `wait_for` exists), sends `signal`, and returns the exit
// status (-1: it did not exit normally).
int interrupt_run(const std::vector<std::string>& args, const fs::path& log, int signal,
                  const fs::path& wait_for = {}) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fd = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    ::dup2(fd, 1);
    ::dup2(fd, 2);
    std::vector<char*> argv{const_cast<char*>(BOUNCE_APP_PATH)};
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(BOUNCE_APP_PATH, argv.data());
    ::_exit(127);
  }
  // The handler is installed when /proc shows the signal as caught (SigCgt, a hex mask).
  const auto caught = [&] {
    std::ifstream status("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(status, line))
      if (line.rfind("SigCgt:", 0) == 0)
        return (std::stoull(line.substr(7), nullptr, 16) >> (signal - 1) & 1) != 0;
    return false;
  };
  for (int i = 0; i < 3000 && !caught(); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  for (int i = 0; i < 3000 && !wait_for.empty() && !fs::exists(wait_for); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  ::kill(pid, signal);
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(CliReliability, SignalsStopCleanlyAndLeaveOutputsAlone) {
  const fs::path dir = scratch_dir("signals");
  const std::pair<int, const char*> signals[] = {{SIGINT, "SIGINT"}, {SIGTERM, "SIGTERM"}};
  for (const auto& [signal, name] : signals) {
    const fs::path out = dir / "old.pfm";
    write(out, "the previous output");
    const std::vector<std::vector<std::string>> commands = {
        {"reference", "cornell", "-W", "64", "-H", "64", "--spp", "1000000", "--time", "60", "-o",
         out.string()},
        {"render", "cornell", "-W", "64", "-H", "64", "--spp", "100000", "-o", out.string()},
        {"sequence", "cornell", "-W", "16", "-H", "16", "--fps", "100", "--to", "900", "--every",
         "1000", "-o", (dir / "seq_%05d.pfm").string()},
    };
    for (const auto& args : commands) {
      const int status = interrupt_run(args, dir / "log.txt", signal);
      const std::string log = read(dir / "log.txt");
      EXPECT_EQ(status, 128 + signal) << args[0] << " " << name << "\n" << log;
      EXPECT_NE(log.find(std::string("bounce: interrupted by ") + name), std::string::npos)
          << args[0] << "\n"
          << log;
      EXPECT_EQ(read(out), "the previous output") << args[0];
      for (const auto& entry : fs::directory_iterator(dir))
        EXPECT_EQ(entry.path().filename().string().find(".tmp-"), std::string::npos)
            << args[0] << " left " << entry.path();
    }
  }
}

TEST(CliReliability, AnInterruptedReferenceResumesFromItsCheckpointToTheSameImage) {
  const fs::path dir = scratch_dir("checkpoint");
  const std::string ck = (dir / "cornell.ckpt").string();
  const auto reference = [&](int spp, const fs::path& out, bool checkpoint) {
    std::string args =
        "reference cornell -W 24 -H 24 --spp " + std::to_string(spp) + " -o " + out.string();
    if (checkpoint) args += " --checkpoint " + ck;
    return run(args);
  };
  // Interrupted after its first pass (the first checkpoint): the samples so far are saved, and
  // the run says how to go on.
  const int status = interrupt_run(
      {"reference", "cornell", "-W", "24", "-H", "24", "--spp", "1000000", "--checkpoint", ck,
       "--checkpoint-every", "0", "-o", (dir / "never.pfm").string()},
      dir / "log.txt", SIGINT);
  const std::string log = read(dir / "log.txt");
  EXPECT_EQ(status, 128 + SIGINT) << log;
  EXPECT_NE(log.find("run the same command to resume"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "never.pfm"));
  const std::string saved = read(ck);
  const size_t at = saved.find("\nspp=");
  ASSERT_NE(at, std::string::npos);
  const int spp = std::stoi(saved.substr(at + 5));
  ASSERT_GT(spp, 0);
  // Resumed to a few more samples, it equals one uninterrupted run of that many.
  const Result resumed = reference(spp + 3, dir / "resumed.pfm", true);
  ASSERT_EQ(resumed.status, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("resuming"), std::string::npos) << resumed.output;
  ASSERT_EQ(reference(spp + 3, dir / "whole.pfm", false).status, 0);
  EXPECT_EQ(read(dir / "resumed.pfm"), read(dir / "whole.pfm"));
  // Another run's settings, a damaged file or too few samples asked for: clear errors.
  const Result other = run("reference cornell -W 24 -H 24 --seed 9 --spp 99999 --checkpoint " + ck);
  EXPECT_EQ(other.status, 1);
  EXPECT_NE(other.output.find("made with seed=0, this run has seed=9"), std::string::npos)
      << other.output;
  const Result fewer = reference(spp, dir / "fewer.pfm", true);
  EXPECT_EQ(fewer.status, 1);
  EXPECT_NE(fewer.output.find("already taken"), std::string::npos) << fewer.output;
  write(ck, saved.substr(0, saved.size() - 100));
  const Result damaged = reference(spp + 9, dir / "damaged.pfm", true);
  EXPECT_EQ(damaged.status, 1);
  EXPECT_NE(damaged.output.find("damaged reference checkpoint"), std::string::npos)
      << damaged.output;
  write(ck, "not a checkpoint");
  EXPECT_NE(reference(spp + 9, dir / "x.pfm", true).output.find("not a bounce reference"),
            std::string::npos);
}

// info and bench say what a technique keeps beyond its per-pixel buffers.
TEST(CliReliability, InfoAndBenchReportTechniqueMemory) {
  const Result info = run("info cornell");
  EXPECT_EQ(info.status, 0) << info.output;
  // lhb's default buffers: 320 directions x 128^2 texels x (16 x 8 + 1) bytes = 645.0 MiB.
  EXPECT_NE(info.output.find("lhb 645.0 MiB"), std::string::npos) << info.output;
  const Result bench = run("bench cornell -t lhb -W 16 -H 16 -n 1 --warmup 0 -p size=32");
  EXPECT_EQ(bench.status, 0) << bench.output;
  // 320 x 32^2 x 129 bytes = 40.3 MiB.
  EXPECT_NE(bench.output.find("technique data (bound)"), std::string::npos) << bench.output;
  EXPECT_NE(bench.output.find("40.3 MiB"), std::string::npos) << bench.output;
  // Beside the bound, what the process holds: at least the buffers themselves.
  const size_t resident = bench.output.find("resident memory");
  ASSERT_NE(resident, std::string::npos) << bench.output;
  EXPECT_GE(std::stod(bench.output.substr(resident + 16)), 40.3) << bench.output;
}

}  // namespace
}  // namespace bounce
