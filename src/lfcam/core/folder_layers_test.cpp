// The source folders' dependencies point one way (../shared/DESIGN.md, "Suggested shape"): the
// folders under src/lfcam, as a graph of which folder's code includes which folder's headers, has
// no cycle, so that each folder has a floor and uses only what lies below it. Tests, fuzz targets
// and test-support headers (a name with "test" in it) may reach upward and are left out.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <string>
#include <vector>

namespace lfcam {
namespace {

namespace fs = std::filesystem;

// folder -> folder it includes -> the first file that does.
using Graph = std::map<std::string, std::map<std::string, std::string>>;

// The folder of an `#include "lfcam/FOLDER/..."` line, or empty. (Plain string work: GCC 12's
// std::regex trips -Wmaybe-uninitialized under the sanitizers' -O1.)
std::string IncludedFolder(const std::string& line) {
  std::size_t at = line.find_first_not_of(" \t");
  if (at == std::string::npos || line[at] != '#') return "";
  at = line.find_first_not_of(" \t", at + 1);
  if (at == std::string::npos || line.compare(at, 7, "include") != 0) return "";
  at = line.find('"', at + 7);
  const std::string prefix = "\"lfcam/";
  if (at == std::string::npos || line.compare(at, prefix.size(), prefix) != 0) return "";
  const std::size_t start = at + prefix.size(), end = line.find('/', start);
  return end == std::string::npos ? "" : line.substr(start, end - start);
}

Graph IncludeGraph() {
  Graph graph;
  const fs::path root = fs::path(LFCAM_SOURCE_DIR) / "src" / "lfcam";
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file()) continue;
    const fs::path& path = entry.path();
    const std::string name = path.filename().string();
    if (path.extension() != ".h" && path.extension() != ".cpp") continue;
    if (name.find("test") != std::string::npos || name.find("_fuzz") != std::string::npos) continue;
    const std::string folder = fs::relative(path, root).begin()->string();
    graph[folder];
    std::ifstream in(path);
    std::string line;
    while (std::getline(in, line)) {
      const std::string included = IncludedFolder(line);
      if (!included.empty() && included != folder)
        graph[folder].emplace(included, fs::relative(path, root).string());
    }
  }
  return graph;
}

// A cycle through the graph, as "a -> b (file) -> ... -> a", or empty.
std::string FindCycle(const Graph& graph) {
  std::map<std::string, int> state;  // 0 unvisited, 1 on the path, 2 done
  std::vector<std::string> path;
  std::string cycle;
  std::function<bool(const std::string&)> visit = [&](const std::string& folder) {
    state[folder] = 1;
    path.push_back(folder);
    const auto found = graph.find(folder);
    if (found != graph.end())
      for (const auto& [next, file] : found->second) {
        if (state[next] == 1) {
          const auto start = std::find(path.begin(), path.end(), next);
          for (auto it = start; it != path.end(); ++it) {
            const auto& edges = graph.at(*it);
            const std::string& to = it + 1 != path.end() ? *(it + 1) : next;
            cycle += *it + " -> " + to + " (" + edges.at(to) + ") ";
          }
          return true;
        }
        if (state[next] == 0 && visit(next)) return true;
      }
    path.pop_back();
    state[folder] = 2;
    return false;
  };
  for (const auto& [folder, edges] : graph)
    if (state[folder] == 0 && visit(folder)) break;
  return cycle;
}

TEST(FolderLayers, DependenciesPointOneWay) {
  const Graph graph = IncludeGraph();
  ASSERT_GE(graph.size(), 10u) << "the source folders were not found under " << LFCAM_SOURCE_DIR;
  const std::string cycle = FindCycle(graph);
  EXPECT_TRUE(cycle.empty()) << "the folders include each other in a cycle: " << cycle;
  // What the design says in so many words: the shared data model (the session's manifest and
  // the boards) lies below the stages, on the core alone; the node's protocol belongs to the node,
  // which the host (capture/) depends on and never the other way; the simulator knows nothing
  // of the nodes or the host that use it.
  const auto uses = [&](const std::string& a, const std::string& b) {
    return graph.count(a) && graph.at(a).count(b);
  };
  for (const auto& [to, file] : graph.at("session"))
    EXPECT_EQ(to, "core") << "session/ includes " << to << "/ (" << file << ")";
  EXPECT_FALSE(uses("node", "capture")) << graph.at("node").at("capture");
  EXPECT_FALSE(uses("sim", "node"));
  EXPECT_FALSE(uses("sim", "capture"));
  EXPECT_TRUE(uses("capture", "node"));  // the host speaks the node's protocol
}

// The check itself: include lines are read as the compiler reads them, and a graph with a cycle
// is caught, and named.
TEST(FolderLayers, ACycleIsFoundAndNamed) {
  EXPECT_EQ(IncludedFolder("#include \"lfcam/core/error.h\""), "core");
  EXPECT_EQ(IncludedFolder("  #  include \"lfcam/sim/scene.h\"  // why"), "sim");
  EXPECT_EQ(IncludedFolder("#include <lfcam/core/error.h>"), "");
  EXPECT_EQ(IncludedFolder("// #include \"lfcam/core/error.h\""), "");
  EXPECT_EQ(IncludedFolder("#include \"lfcam/top_level.h\""), "");
  Graph graph;
  graph["a"]["b"] = "a/x.h";
  graph["b"]["c"] = "b/y.cpp";
  graph["c"];
  EXPECT_TRUE(FindCycle(graph).empty());
  graph["c"]["a"] = "c/z.h";
  const std::string cycle = FindCycle(graph);
  EXPECT_NE(cycle.find("c -> a (c/z.h)"), std::string::npos) << cycle;
}

}  // namespace
}  // namespace lfcam
