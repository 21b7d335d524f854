#include "tetgen/tetgen_run.h"

#include <cstdint>
#include <cstring>

#include <tetgen.h>

#include "deformcd/error.h"

namespace deformcd::detail {

namespace {

void fill_input(const SurfaceMesh& surface, tetgenio& in) {
  in.firstnumber = 0;
  in.numberofpoints = static_cast<int>(surface.vertices.size());
  in.pointlist = new REAL[surface.vertices.size() * 3];
  for (std::size_t i = 0; i < surface.vertices.size(); ++i) {
    for (int k = 0; k < 3; ++k)
      in.pointlist[3 * i + k] = surface.vertices[i][k];
  }
  in.numberoffacets = static_cast<int>(surface.triangles.size());
  in.facetlist = new tetgenio::facet[surface.triangles.size()];
  for (std::size_t i = 0; i < surface.triangles.size(); ++i) {
    tetgenio::facet& f = in.facetlist[i];
    tetgenio::init(&f);
    f.numberofpolygons = 1;
    f.polygonlist = new tetgenio::polygon[1];
    tetgenio::init(&f.polygonlist[0]);
    f.polygonlist[0].numberofvertices = 3;
    f.polygonlist[0].vertexlist = new int[3];
    for (int k = 0; k < 3; ++k) {
      f.polygonlist[0].vertexlist[k] = static_cast<int>(surface.triangles[i][k]);
    }
  }
}

template <class T>
void append_raw(std::string& out, const T* data, std::size_t count) {
  if (count > 0) out.append(reinterpret_cast<const char*>(data), sizeof(T) * count);
}

// Layout: 4 x int64 counts (points, tetrahedra, corners, faces), then the three arrays.
std::string serialize(const tetgenio& out) {
  std::string bytes;
  const std::int64_t counts[4] = {out.numberofpoints, out.numberoftetrahedra, out.numberofcorners,
                                  out.numberoftrifaces};
  append_raw(bytes, counts, 4);
  append_raw(bytes, out.pointlist, static_cast<std::size_t>(counts[0]) * 3);
  append_raw(bytes, out.tetrahedronlist, static_cast<std::size_t>(counts[1] * counts[2]));
  append_raw(bytes, out.trifacelist, static_cast<std::size_t>(counts[3]) * 3);
  return bytes;
}

class RawReader {
 public:
  explicit RawReader(const std::string& bytes) : bytes_(bytes) {}
  template <class T>
  void read(T* data, std::size_t count) {
    const std::size_t size = sizeof(T) * count;
    if (pos_ + size > bytes_.size()) throw Error("internal: truncated TetGen result");
    if (size > 0) std::memcpy(data, bytes_.data() + pos_, size);
    pos_ += size;
  }

 private:
  const std::string& bytes_;
  std::size_t pos_ = 0;
};

}  // namespace

int run_tetgen(const SurfaceMesh& surface, const std::string& switches, std::string& output) {
  try {
    tetgenio in, diagnosis, out;
    fill_input(surface, in);
    // TetGen can crash meshing a self-intersecting surface; its diagnosis mode finds them.
    tetgenbehavior diagnose;
    std::string diagnose_switches = "pzQd";
    if (!diagnose.parse_commandline(diagnose_switches.data())) return kBadSwitches;
    ::tetrahedralize(&diagnose, &in, &diagnosis);
    if (diagnosis.numberoftrifaces > 0) {
      output = std::to_string(diagnosis.numberoftrifaces);
      return kSelfIntersecting;
    }
    tetgenbehavior behaviour;
    std::string run_switches = switches;
    if (!behaviour.parse_commandline(run_switches.data())) return kBadSwitches;
    ::tetrahedralize(&behaviour, &in, &out);
    output = serialize(out);
    return 0;
  } catch (int code) {  // libtet is built with TETLIBRARY: terminatetetgen() throws its code
    return code;
  }
}

TetMesh deserialize_tetgen_output(const std::string& bytes) {
  RawReader in(bytes);
  std::int64_t counts[4];
  in.read(counts, 4);
  for (std::int64_t c : counts) {
    if (c < 0) throw Error("internal: corrupt TetGen result");
  }
  const auto points = static_cast<std::size_t>(counts[0]);
  const auto tets = static_cast<std::size_t>(counts[1]);
  const auto corners = static_cast<std::size_t>(counts[2]);
  const auto faces = static_cast<std::size_t>(counts[3]);
  if (tets > 0 && corners < 4) throw Error("internal: corrupt TetGen result");

  std::vector<double> xyz(points * 3);
  in.read(xyz.data(), xyz.size());
  std::vector<int> tet_nodes(tets * corners);
  in.read(tet_nodes.data(), tet_nodes.size());
  std::vector<int> face_nodes(faces * 3);
  in.read(face_nodes.data(), face_nodes.size());

  TetMesh mesh;
  mesh.nodes.resize(points);
  for (std::size_t i = 0; i < points; ++i)
    mesh.nodes[i] = {xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]};
  mesh.tetrahedra.resize(tets);
  for (std::size_t i = 0; i < tets; ++i) {
    for (std::size_t k = 0; k < 4; ++k) {
      mesh.tetrahedra[i][k] = static_cast<std::uint32_t>(tet_nodes[corners * i + k]);
    }
  }
  mesh.faces.resize(faces);
  for (std::size_t i = 0; i < faces; ++i) {
    for (std::size_t k = 0; k < 3; ++k) {
      mesh.faces[i][k] = static_cast<std::uint32_t>(face_nodes[3 * i + k]);
    }
  }
  return mesh;
}

std::string explain_tetgen_failure(int code) {
  switch (code) {
    case 1:
      return "TetGen ran out of memory";
    case 2:
      return "TetGen hit an internal error";
    case 3:
      return "the surface intersects itself";
    case 4:
      return "the surface has a feature too small for TetGen's tolerance";
    case 5:
      return "two input faces are too close to each other";
    case 10:
      return "TetGen rejected the input";
    case kBadSwitches:
      return "TetGen rejected its switches (internal error)";
    case 120:
      return "the TetGen result could not be passed back";
    case 121:
      return "an unexpected exception in the TetGen process";
    default:
      return "TetGen failed with code " + std::to_string(code);
  }
}

}  // namespace deformcd::detail
