#include "mesh/connected_components.h"

#include <numeric>

namespace kerf::mesh {
namespace {

class DisjointSets {
 public:
  explicit DisjointSets(std::size_t n) : parent_(n) {
    std::iota(parent_.begin(), parent_.end(), 0u);
  }
  std::uint32_t Find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];  // path halving
      x = parent_[x];
    }
    return x;
  }
  void Union(std::uint32_t a, std::uint32_t b) {
    a = Find(a);
    b = Find(b);
    if (a != b) parent_[std::max(a, b)] = std::min(a, b);
  }

 private:
  std::vector<std::uint32_t> parent_;
};

}  // namespace

MeshComponents FindConnectedComponents(const TetMesh& mesh) {
  DisjointSets sets(mesh.vertex_index_bound());
  for (const TetId t : mesh.tets()) {
    const TetVertices& v = mesh.tet(t);
    for (int i = 1; i < 4; ++i) sets.Union(Index(v[0]), Index(v[i]));
  }
  MeshComponents components;
  components.tet_component.assign(mesh.tet_index_bound(), -1);
  std::vector<std::int32_t> label_of_root(mesh.vertex_index_bound(), -1);
  for (const TetId t : mesh.tets()) {
    const std::uint32_t root = sets.Find(Index(mesh.tet(t)[0]));
    if (label_of_root[root] < 0)
      label_of_root[root] = static_cast<std::int32_t>(components.count++);
    components.tet_component[Index(t)] = label_of_root[root];
  }
  return components;
}

}  // namespace kerf::mesh
