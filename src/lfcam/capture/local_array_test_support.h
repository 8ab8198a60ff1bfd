#pragma once
// Tests only: a camera array of real lfcam-node processes (LFCAM_NODE_PATH, set by CMake) on
// loopback ports, one per camera, that a test can kill, restart and misconfigure.
#include <fcntl.h>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>
#include <vector>

#include "lfcam/capture/array_file.h"
#include "lfcam/core/error.h"
#include "lfcam/node/request_signature.h"

extern char** environ;

namespace lfcam::testing {

// GCC says AddressSanitizer with __SANITIZE_ADDRESS__, clang with __has_feature; a sanitizer
// build whose tests' own code is not instrumented says it with LFCAM_TEST_UNDER_ASAN (CMakeLists).
#if defined(LFCAM_TEST_UNDER_ASAN)
#elif defined(__SANITIZE_ADDRESS__)
#define LFCAM_TEST_UNDER_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define LFCAM_TEST_UNDER_ASAN 1
#endif
#endif

// The trigger lead a test asks for. A sanitized build answers every request several times
// slower, and a node refuses, by design, a trigger that reaches it after its time; so under
// AddressSanitizer the same test waits longer rather than failing on the machine's load.
inline double TestTriggerMarginS(double seconds) {
#if defined(LFCAM_TEST_UNDER_ASAN)
  return 5 * seconds;
#else
  return seconds;
#endif
}

class LocalArray {
 public:
  // `backend_args` are every node's camera flags ("--backend", "replay", "--replay", DIR).
  LocalArray(std::filesystem::path dir, int rows, int cols, std::vector<std::string> backend_args)
      : dir_(std::move(dir)), rows_(rows), cols_(cols), backend_args_(std::move(backend_args)) {
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
    std::ofstream(dir_ / "array.key") << NewKeyHex() << "\n";
    std::filesystem::permissions(dir_ / "array.key", std::filesystem::perms::owner_read |
                                                         std::filesystem::perms::owner_write);
    key_ = ReadKeyFile(dir_ / "array.key");
    nodes_.resize(std::size_t(rows * cols));
  }
  ~LocalArray() {
    for (std::size_t i = 0; i < nodes_.size(); ++i) Kill(int(i));
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }

  // The command that runs a node, before its flags (default: this build's lfcam-node), e.g.
  // {"qemu-aarch64-static", "build/node-arm64/lfcam-node"}: the Pis' agent under emulation.
  void SetNodeCommand(std::vector<std::string> command) { command_ = std::move(command); }

  int size() const { return rows_ * cols_; }
  int index(int row, int col) const { return row * cols_ + col; }
  const SharedKey& key() const { return key_; }
  const std::filesystem::path& dir() const { return dir_; }
  std::filesystem::path captures(int i) const { return dir_ / Name(i) / "captures"; }
  std::string address(int i) const {
    return "127.0.0.1:" + std::to_string(nodes_[std::size_t(i)].port);
  }

  // Starts node i (on the port it had before, if it ran before) with `extra` flags.
  void Start(int i, const std::vector<std::string>& extra = {}) {
    Spawn(i, extra);
    WaitReady(i);
  }

  // All at once: the processes start side by side.
  void StartAll(const std::vector<std::string>& extra = {}) {
    for (int i = 0; i < size(); ++i) Spawn(i, extra);
    for (int i = 0; i < size(); ++i) WaitReady(i);
  }

  void Kill(int i, int sig = SIGKILL) {
    Node& n = nodes_[std::size_t(i)];
    if (n.pid <= 0) return;
    ::kill(n.pid, sig);
    int status = 0;
    ::waitpid(n.pid, &status, 0);
    n.pid = -1;
  }

  ArrayConfig Config(int width = 640, int height = 480) const {
    ArrayConfig a;
    a.rows = rows_;
    a.cols = cols_;
    a.key_file = dir_ / "array.key";
    a.settings.width = width;
    a.settings.height = height;
    a.intrinsics_board = BoardSpec(10, 7, 30.0);
    a.world_board = BoardSpec(11, 10, 50.0);
    for (int r = 0; r < rows_; ++r)
      for (int c = 0; c < cols_; ++c) a.nodes.push_back({r, c, address(index(r, c)), 0});
    return a;
  }

  std::filesystem::path WriteArrayFile(int width = 640, int height = 480) const {
    const auto path = dir_ / "array.json";
    lfcam::WriteArrayFile(path, Config(width, height));
    return path;
  }

 private:
  void Spawn(int i, const std::vector<std::string>& extra) {
    Node& n = nodes_[std::size_t(i)];
    Kill(i);
    const std::filesystem::path home = dir_ / Name(i);
    std::filesystem::create_directories(home);
    std::filesystem::remove(home / "port");
    std::vector<std::string> args = command_;
    args.insert(args.end(), {"--listen", "127.0.0.1:" + std::to_string(n.port), "--port-file",
                             (home / "port").string(), "--key-file", (dir_ / "array.key").string(),
                             "--captures", (home / "captures").string(), "--name", Name(i),
                             "--quiet", "--threads", "2", "--min-free-mb", "1"});
    args.insert(args.end(), backend_args_.begin(), backend_args_.end());
    args.insert(args.end(), extra.begin(), extra.end());
    std::vector<char*> argv;
    for (std::string& a : args) argv.push_back(a.data());
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    const std::string log = (home / "log").string();
    posix_spawn_file_actions_addopen(&actions, 1, log.c_str(), O_WRONLY | O_CREAT | O_APPEND, 0644);
    posix_spawn_file_actions_adddup2(&actions, 1, 2);
    pid_t pid = 0;
    const int rc = ::posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
    posix_spawn_file_actions_destroy(&actions);
    if (rc != 0) throw Error("cannot start " + command_.front());
    n.pid = pid;
  }

  void WaitReady(int i) {
    Node& n = nodes_[std::size_t(i)];
    const std::filesystem::path home = dir_ / Name(i);
    const std::string log = (home / "log").string();
    // Sanitized builds start slowly: wait up to 30 s for the port.
    for (int t = 0; t < 3000; ++t) {
      std::ifstream in(home / "port");
      int port = 0;
      if (in >> port && port > 0) {
        n.port = port;
        return;
      }
      int status = 0;
      if (::waitpid(n.pid, &status, WNOHANG) == n.pid) {
        n.pid = -1;
        throw Error(Name(i) + " exited at start; see " + log);
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    throw Error(Name(i) + " did not start; see " + log);
  }

  struct Node {
    pid_t pid = -1;
    int port = 0;
  };
  std::string Name(int i) const {
    char name[32];
    std::snprintf(name, sizeof name, "node-%02d-%02d", i / cols_, i % cols_);
    return name;
  }

  std::filesystem::path dir_;
  int rows_, cols_;
  std::vector<std::string> backend_args_;
  std::vector<std::string> command_ = {LFCAM_NODE_PATH};
  SharedKey key_;
  std::vector<Node> nodes_;
};

}  // namespace lfcam::testing
