#include "sim/abaqus_deck.h"

#include <cmath>

#include "absl/container/flat_hash_map.h"
#include "absl/strings/ascii.h"
#include "absl/strings/str_cat.h"
#include "mesh/io/abaqus_inp_blocks.h"
#include "mesh/io/abaqus_inp_reader.h"
#include "mesh/io/text_scanner.h"

namespace kerf::sim {
namespace {

using mesh::internal::InpDataLine;
using mesh::internal::InpKeywordBlock;
using mesh::internal::ParseDouble;
using mesh::internal::ParseInt;

class DeckReader {
 public:
  DeckReader(absl::string_view text, absl::string_view source) : errors_(text, source) {}

  absl::Status Error(std::size_t offset, absl::string_view message) const {
    return errors_.ErrorAt(offset, message);
  }

  // The vertices a field names: a node id or the name of a node set.
  absl::StatusOr<std::vector<mesh::VertexId>> Nodes(absl::string_view field,
                                                    std::size_t offset) const {
    std::int64_t id = 0;
    if (ParseInt(field, &id)) {
      const auto it = vertex_of_id_.find(id);
      if (it == vertex_of_id_.end())
        return Error(offset, absl::StrCat("node ", id, " is not defined"));
      return std::vector<mesh::VertexId>{it->second};
    }
    const auto set = node_sets_.find(absl::AsciiStrToUpper(field));
    if (set == node_sets_.end()) {
      return Error(offset, absl::StrCat("'", field, "' is neither a node id nor a node set"));
    }
    return set->second;
  }

  absl::StatusOr<double> Number(const InpDataLine& line, std::size_t index,
                                absl::string_view what) const {
    double value = 0;
    if (index >= line.fields.size() || !ParseDouble(line.fields[index], &value) ||
        !std::isfinite(value)) {
      return Error(line.offset,
                   absl::StrCat("expected ", what, " (a finite number) in field ", index + 1));
    }
    return value;
  }

  absl::Status ReadNodeSet(const InpKeywordBlock& block) {
    const std::string name = absl::AsciiStrToUpper(block.Parameter("NSET").value_or(""));
    if (name.empty()) return Error(block.offset, "*NSET needs NSET=name");
    const bool generate = block.Parameter("GENERATE").has_value();
    std::vector<mesh::VertexId>& set = node_sets_[name];
    for (const InpDataLine& line : block.lines) {
      if (generate) {
        std::int64_t first = 0, last = 0, step = 1;
        if (line.fields.size() < 2 || !ParseInt(line.fields[0], &first) ||
            !ParseInt(line.fields[1], &last) ||
            (line.fields.size() > 2 && !ParseInt(line.fields[2], &step)) || step <= 0 ||
            last < first) {
          return Error(line.offset, "expected 'first, last[, step]' with first <= last, step > 0");
        }
        for (std::int64_t id = first; id <= last; id += step) {
          absl::StatusOr<std::vector<mesh::VertexId>> v = Nodes(absl::StrCat(id), line.offset);
          if (!v.ok()) return v.status();
          set.insert(set.end(), v->begin(), v->end());
        }
        continue;
      }
      for (const absl::string_view field : line.fields) {
        absl::StatusOr<std::vector<mesh::VertexId>> v = Nodes(field, line.offset);
        if (!v.ok()) return v.status();
        set.insert(set.end(), v->begin(), v->end());
      }
    }
    return absl::OkStatus();
  }

  absl::Status ReadBoundary(const InpKeywordBlock& block, fem::BoundaryConditions* bc) const {
    for (const InpDataLine& line : block.lines) {
      // node-or-set, first dof[, last dof[, value]]
      absl::StatusOr<std::vector<mesh::VertexId>> nodes =
          line.fields.empty() ? Error(line.offset, "empty *BOUNDARY line")
                              : Nodes(line.fields[0], line.offset);
      if (!nodes.ok()) return nodes.status();
      std::int64_t first = 0, last = 0;
      double value = 0;
      if (line.fields.size() < 2 || !ParseInt(line.fields[1], &first)) {
        return Error(line.offset, "expected 'node or set, first dof[, last dof[, value]]'");
      }
      last = first;
      if (line.fields.size() > 2 && !line.fields[2].empty() && !ParseInt(line.fields[2], &last)) {
        return Error(line.offset, "expected an integer last dof in field 3");
      }
      if (line.fields.size() > 3) {
        absl::StatusOr<double> v = Number(line, 3, "a displacement");
        if (!v.ok()) return v.status();
        value = *v;
      }
      if (first < 1 || last > 3 || last < first) {
        return Error(line.offset, absl::StrCat("dofs ", first, " to ", last,
                                               " are not translations: kerf supports dofs 1-3"));
      }
      for (const mesh::VertexId v : *nodes) {
        for (std::int64_t dof = first; dof <= last; ++dof) {
          bc->prescribed.push_back({v, static_cast<int>(dof - 1), value});
        }
      }
    }
    return absl::OkStatus();
  }

  absl::Status ReadConcentratedLoads(const InpKeywordBlock& block,
                                     fem::BoundaryConditions* bc) const {
    for (const InpDataLine& line : block.lines) {
      absl::StatusOr<std::vector<mesh::VertexId>> nodes =
          line.fields.empty() ? Error(line.offset, "empty *CLOAD line")
                              : Nodes(line.fields[0], line.offset);
      if (!nodes.ok()) return nodes.status();
      std::int64_t dof = 0;
      if (line.fields.size() != 3 || !ParseInt(line.fields[1], &dof) || dof < 1 || dof > 3) {
        return Error(line.offset, "expected 'node or set, dof (1-3), value'");
      }
      absl::StatusOr<double> value = Number(line, 2, "a force");
      if (!value.ok()) return value.status();
      for (const mesh::VertexId v : *nodes) {
        Eigen::Vector3d force = Eigen::Vector3d::Zero();
        force[static_cast<int>(dof - 1)] = *value;
        bc->loads.push_back({v, force});
      }
    }
    return absl::OkStatus();
  }

  absl::Status ReadDistributedLoads(const InpKeywordBlock& block,
                                    fem::BoundaryConditions* bc) const {
    for (const InpDataLine& line : block.lines) {
      if (line.fields.size() != 6 || absl::AsciiStrToUpper(line.fields[1]) != "GRAV") {
        return Error(line.offset,
                     "expected 'elset, GRAV, magnitude, dx, dy, dz': kerf supports "
                     "only gravity loads");
      }
      Eigen::Vector3d direction;
      absl::StatusOr<double> magnitude = Number(line, 2, "a gravity magnitude");
      if (!magnitude.ok()) return magnitude.status();
      for (int c = 0; c < 3; ++c) {
        absl::StatusOr<double> d = Number(line, 3 + static_cast<std::size_t>(c), "a direction");
        if (!d.ok()) return d.status();
        direction[c] = *d;
      }
      bc->gravity += *magnitude * direction;
    }
    return absl::OkStatus();
  }

  absl::flat_hash_map<std::int64_t, mesh::VertexId> vertex_of_id_;
  absl::flat_hash_map<std::string, std::vector<mesh::VertexId>> node_sets_;

 private:
  mesh::internal::TextScanner errors_;
};

}  // namespace

absl::StatusOr<StaticDeck> ParseStaticDeck(absl::string_view text, absl::string_view source) {
  absl::StatusOr<mesh::TetMeshData> data = mesh::ParseAbaqusInpMesh(text, source);
  if (!data.ok()) return data.status();
  absl::StatusOr<std::vector<InpKeywordBlock>> blocks =
      mesh::internal::ParseInpKeywordBlocks(text, source);
  if (!blocks.ok()) return blocks.status();
  absl::StatusOr<mesh::TetMesh> built = mesh::BuildTetMesh(*data);
  if (!built.ok()) return built.status();

  StaticDeck deck{*std::move(built), data->point_ids, {}, {}};
  DeckReader reader(text, source);
  for (std::size_t i = 0; i < deck.node_ids.size(); ++i) {
    reader.vertex_of_id_[deck.node_ids[i]] = static_cast<mesh::VertexId>(i);
  }
  bool have_elastic = false, have_density = false, have_section = false, in_step = false;
  std::string material_name, element_set;
  for (const InpKeywordBlock& block : *blocks) {
    const std::string& k = block.keyword;
    absl::Status status;
    if (k == "HEADING" || k == "ELEMENT") {
      // The heading is a title; elements were read with the mesh.
      if (k == "ELEMENT")
        element_set = absl::AsciiStrToUpper(block.Parameter("ELSET").value_or(""));
    } else if (k == "NODE") {
      if (const auto set = block.Parameter("NSET")) {
        std::vector<mesh::VertexId>& nodes = reader.node_sets_[absl::AsciiStrToUpper(*set)];
        for (const InpDataLine& line : block.lines) {
          std::int64_t id = 0;
          ParseInt(line.fields[0], &id);  // validated by the mesh reader
          nodes.push_back(reader.vertex_of_id_.at(id));
        }
      }
    } else if (k == "NSET") {
      status = reader.ReadNodeSet(block);
    } else if (k == "MATERIAL") {
      if (!material_name.empty()) return reader.Error(block.offset, "kerf supports one *MATERIAL");
      material_name = absl::AsciiStrToUpper(block.Parameter("NAME").value_or(""));
    } else if (k == "ELASTIC") {
      const std::string type = absl::AsciiStrToUpper(block.Parameter("TYPE").value_or("ISO"));
      if (type != "ISO" || block.lines.size() != 1 || block.lines[0].fields.size() < 2) {
        return reader.Error(block.offset, "expected *ELASTIC (isotropic) with one line 'E, nu'");
      }
      absl::StatusOr<double> e = reader.Number(block.lines[0], 0, "Young's modulus");
      absl::StatusOr<double> nu = reader.Number(block.lines[0], 1, "Poisson's ratio");
      if (!e.ok()) return e.status();
      if (!nu.ok()) return nu.status();
      deck.material.youngs_modulus = *e;
      deck.material.poisson_ratio = *nu;
      have_elastic = true;
    } else if (k == "DENSITY") {
      if (block.lines.size() != 1) return reader.Error(block.offset, "expected one *DENSITY line");
      absl::StatusOr<double> rho = reader.Number(block.lines[0], 0, "density");
      if (!rho.ok()) return rho.status();
      deck.material.density = *rho;
      have_density = true;
    } else if (k == "SOLID SECTION") {
      if (have_section) return reader.Error(block.offset, "kerf supports one *SOLID SECTION");
      const std::string set = absl::AsciiStrToUpper(block.Parameter("ELSET").value_or(""));
      const std::string material = absl::AsciiStrToUpper(block.Parameter("MATERIAL").value_or(""));
      if (set != element_set || material != material_name) {
        return reader.Error(block.offset,
                            absl::StrCat("*SOLID SECTION must assign material ", material_name,
                                         " to element set ", element_set, ", every element"));
      }
      have_section = true;
    } else if (k == "STEP") {
      if (in_step) return reader.Error(block.offset, "kerf supports one *STEP");
      in_step = true;
    } else if (k == "STATIC" || k == "END STEP") {
      if (!in_step) return reader.Error(block.offset, absl::StrCat("*", k, " outside *STEP"));
    } else if (k == "BOUNDARY") {
      status = reader.ReadBoundary(block, &deck.conditions);
    } else if (k == "CLOAD") {
      status = reader.ReadConcentratedLoads(block, &deck.conditions);
    } else if (k == "DLOAD") {
      status = reader.ReadDistributedLoads(block, &deck.conditions);
    } else if (k == "NODE PRINT") {
      // An output request: kerf static prints every displacement.
    } else {
      return reader.Error(block.offset,
                          absl::StrCat("*", k,
                                       " is not supported by kerf static; the subset is "
                                       "in ../shared/design/accuracy.md"));
    }
    if (!status.ok()) return status;
  }
  if (!have_elastic || !have_density || !have_section) {
    return reader.Error(text.size(),
                        "expected *MATERIAL with *ELASTIC and *DENSITY, and a "
                        "*SOLID SECTION");
  }
  if (absl::Status s = fem::ValidateMaterial(deck.material); !s.ok()) return s;
  return deck;
}

}  // namespace kerf::sim
