#include "matpoint/io/vtk_writer.hpp"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <iomanip>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <utility>

#include "matpoint/io/atomic_file.hpp"
#include "matpoint/material/hencky_plasticity.hpp"

namespace matpoint {

namespace {

/// The binary part of a .vtu file in VTK's appended format: every DataArray is a block of
/// zlib-compressed bytes behind a UInt64 header [number of blocks, block size, size of the last
/// block, compressed size of each block] (VTK's vtkZLibDataCompressor layout; 64-bit sizes do not
/// wrap for arrays above 4 GiB, as 32-bit ones would). Blocks are compressed in parallel.
class AppendedData {
 public:
  static constexpr std::size_t kBlock = 1 << 16;  // uncompressed bytes per block
  static constexpr int kLevel = 1;                // zlib level: see docs/output.md "Particle files"

  /// The <DataArray .../> element of `values`, whose bytes are appended here.
  template <class T>
  std::string array(const std::string& name, const char* type, int components, const std::vector<T>& values,
                    const std::vector<std::string>& component_names = {}) {
    std::ostringstream out;
    out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\""
        << components << "\"";
    for (std::size_t c = 0; c < component_names.size(); ++c)
      out << " ComponentName" << c << "=\"" << component_names[c] << "\"";
    out << " format=\"appended\" offset=\"" << bytes_.size() << "\"/>\n";
    append(reinterpret_cast<const unsigned char*>(values.data()), values.size() * sizeof(T));
    return out.str();
  }

  [[nodiscard]] const std::string& bytes() const { return bytes_; }

 private:
  void append(const unsigned char* data, std::size_t size) {
    const std::size_t blocks = (size + kBlock - 1) / kBlock;
    std::vector<std::string> compressed(blocks);
#pragma omp parallel for schedule(dynamic) if (blocks > 1)
    for (std::size_t b = 0; b < blocks; ++b) {
      const std::size_t length = std::min(kBlock, size - b * kBlock);
      uLongf out_length = compressBound(static_cast<uLong>(length));
      compressed[b].resize(out_length);
      const int status = compress2(reinterpret_cast<Bytef*>(compressed[b].data()), &out_length,
                                   data + b * kBlock, static_cast<uLong>(length), kLevel);
      if (status != Z_OK) compressed[b].clear();  // reported below, outside the parallel loop
      compressed[b].resize(status == Z_OK ? out_length : 0);
    }
    std::vector<std::uint64_t> header{blocks, kBlock, size % kBlock};
    for (const auto& c : compressed) {
      if (c.empty()) throw std::runtime_error("zlib could not compress a .vtu data array");
      header.push_back(c.size());
    }
    bytes_.append(reinterpret_cast<const char*>(header.data()), header.size() * sizeof(std::uint64_t));
    for (const auto& c : compressed) bytes_ += c;
  }

  std::string bytes_;
};

/// A whole .vtu file: the XML `body` (the <Piece> with its DataArray elements) and the data.
std::string vtu_file(const std::string& piece, const AppendedData& data) {
  std::string out =
      "<?xml version=\"1.0\"?>\n"
      "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\" "
      "compressor=\"vtkZLibDataCompressor\">\n"
      "  <UnstructuredGrid>\n" +
      piece + "  </UnstructuredGrid>\n  <AppendedData encoding=\"raw\">\n   _";
  out += data.bytes();
  out += "\n  </AppendedData>\n</VTKFile>\n";
  return out;
}

template <int D>
std::vector<double> padded_vectors(const std::vector<Vec<D>>& v) {
  std::vector<double> out(3 * v.size(), 0.0);
  for (std::size_t p = 0; p < v.size(); ++p)
    for (int a = 0; a < D; ++a) out[3 * p + a] = v[p][a];
  return out;
}

template <int D, class Fn>
std::vector<double> padded_tensors(std::size_t n, Fn&& tensor_of) {
  std::vector<double> out(9 * n, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const Mat<D> t = tensor_of(p);
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) out[9 * p + 3 * i + j] = t(i, j);
  }
  return out;
}

template <class Fn>
std::vector<double> scalars(std::size_t n, Fn&& value_of) {
  std::vector<double> out(n);
  for (std::size_t p = 0; p < n; ++p) out[p] = value_of(p);
  return out;
}

/// Cauchy stress as 3 x 3 per particle; in 2-D (plane strain) with sigma_zz.
template <int D>
std::vector<double> stress_3x3(const ParticleSet<D>& ps) {
  auto out = padded_tensors<D>(ps.size(), [&](std::size_t p) { return ps.stress[p]; });
  if constexpr (D == 2)
    for (std::size_t p = 0; p < ps.size(); ++p) out[9 * p + 8] = ps.stress_zz[p];
  return out;
}

/// The three normal stresses (sigma_zz of plane strain in 2-D; 0 outside the model's dimensions).
template <int D>
Vec<3> normal_stresses(const ParticleSet<D>& ps, std::size_t p) {
  Vec<3> s = Vec<3>::Zero();
  for (int a = 0; a < D; ++a) s[a] = ps.stress[p](a, a);
  if constexpr (D == 2) s[2] = ps.stress_zz[p];
  return s;
}
/// Pressure -tr(sigma)/3 (compression positive).
template <int D>
double pressure(const ParticleSet<D>& ps, std::size_t p) {
  return -normal_stresses(ps, p).sum() / 3.0;
}
/// von Mises stress sqrt(3/2 s : s), s = dev(sigma) of the 3 x 3 stress.
template <int D>
double von_mises(const ParticleSet<D>& ps, std::size_t p) {
  const Vec<3> normal = normal_stresses(ps, p);
  const double mean = normal.sum() / 3.0;
  double ss = (normal.array() - mean).square().sum();
  for (int i = 0; i < D; ++i)
    for (int j = 0; j < D; ++j)
      if (i != j) ss += ps.stress[p](i, j) * ps.stress[p](i, j);
  return std::sqrt(1.5 * ss);
}

bool wanted(const std::vector<std::string>& fields, const std::string& name) {
  return fields.empty() || std::find(fields.begin(), fields.end(), name) != fields.end();
}

}  // namespace

template <int D>
std::string particles_vtu(const ParticleSet<D>& ps, const std::vector<std::string>& fields, bool displacement,
                          const std::vector<std::string>& state_names) {
  const std::size_t n = ps.size();
  AppendedData data;
  std::ostringstream point_data;
  if (wanted(fields, "velocity")) point_data << data.array("velocity", "Float64", 3, padded_vectors<D>(ps.v));
  if (wanted(fields, "displacement") && displacement) {  // u = x - X
    std::vector<Vec<D>> u(n);
    for (std::size_t p = 0; p < n; ++p) u[p] = ps.x[p] - ps.x0[p];
    point_data << data.array("displacement", "Float64", 3, padded_vectors<D>(u));
  }
  if (wanted(fields, "stress")) point_data << data.array("stress", "Float64", 9, stress_3x3(ps));
  if (wanted(fields, "deformation_gradient"))
    point_data << data.array("deformation_gradient", "Float64", 9,
                             padded_tensors<D>(n, [&](std::size_t p) { return ps.F[p]; }));
  if (wanted(fields, "strain"))  // Green-Lagrange strain E = (F^T F - I) / 2
    point_data << data.array("strain", "Float64", 9, padded_tensors<D>(n, [&](std::size_t p) {
                               return Mat<D>(0.5 * (ps.F[p].transpose() * ps.F[p] - Mat<D>::Identity()));
                             }));
  if (wanted(fields, "jacobian"))
    point_data << data.array("jacobian", "Float64", 1,
                             scalars(n, [&](std::size_t p) { return ps.F[p].determinant(); }));
  if (wanted(fields, "mass")) point_data << data.array("mass", "Float64", 1, ps.mass);
  if (wanted(fields, "volume"))
    point_data << data.array("volume", "Float64", 1, scalars(n, [&](std::size_t p) { return ps.volume(p); }));
  if (wanted(fields, "material")) point_data << data.array("material", "Int32", 1, ps.material);
  if (wanted(fields, "body")) point_data << data.array("body", "Int32", 1, ps.body);
  if (wanted(fields, "id")) {
    std::vector<std::int64_t> ids(ps.id.begin(), ps.id.end());
    point_data << data.array("id", "Int64", 1, ids);
  }
  if (wanted(fields, "state") && ps.state_stride > 0)
    point_data << data.array("state", "Float64", ps.state_stride, ps.state, state_names);
  if (wanted(fields, "pressure"))  // p = -tr(sigma) / 3 of the 3 x 3 stress (sigma_zz in plane strain)
    point_data << data.array("pressure", "Float64", 1,
                             scalars(n, [&](std::size_t p) { return pressure(ps, p); }));
  if (wanted(fields, "von_mises"))
    point_data << data.array("von_mises", "Float64", 1,
                             scalars(n, [&](std::size_t p) { return von_mises(ps, p); }));
  if (wanted(fields, "plastic_strain"))
    point_data << data.array("plastic_strain", "Float64", 1, scalars(n, [&](std::size_t p) {
                               return ps.plastic(p) ? ps.state[p * ps.state_stride + kEquivalentPlasticStrain]
                                                    : 0.0;
                             }));
  // has_temperature: a rank without particles declares the array as the others do
  if (wanted(fields, "temperature") && (ps.has_temperature || !ps.temperature.empty()))
    point_data << data.array("temperature", "Float64", 1, ps.temperature);
  if (wanted(fields, "yield_state")) {
    std::vector<std::int32_t> state(n, 0);
    for (std::size_t p = 0; p < n; ++p)
      if (ps.plastic(p)) state[p] = static_cast<std::int32_t>(ps.state[p * ps.state_stride + kYieldState]);
    point_data << data.array("yield_state", "Int32", 1, state);
  }

  std::vector<std::int64_t> connectivity(n), offsets(n);
  std::vector<std::uint8_t> types(n, 1);  // VTK_VERTEX
  for (std::size_t p = 0; p < n; ++p) {
    connectivity[p] = static_cast<std::int64_t>(p);
    offsets[p] = static_cast<std::int64_t>(p + 1);
  }
  std::ostringstream piece;
  piece << "    <Piece NumberOfPoints=\"" << n << "\" NumberOfCells=\"" << n << "\">\n"
        << "      <PointData>\n"
        << point_data.str() << "      </PointData>\n"
        << "      <Points>\n"
        << data.array("Points", "Float64", 3, padded_vectors<D>(ps.x)) << "      </Points>\n"
        << "      <Cells>\n"
        << data.array("connectivity", "Int64", 1, connectivity) << data.array("offsets", "Int64", 1, offsets)
        << data.array("types", "UInt8", 1, types) << "      </Cells>\n"
        << "    </Piece>\n";
  return vtu_file(piece.str(), data);
}

template <int D>
std::string domains_vtu(const std::vector<typename ParticleSet<D>::Corners>& domains,
                        const ParticleSet<D>& ps) {
  constexpr int C = ParticleSet<D>::kCorners;
  // Tensor-order corner k -> VTK's counter-clockwise (2-D) / bottom-then-top (3-D) numbering.
  constexpr std::array<int, 8> vtk_order{0, 1, 3, 2, 4, 5, 7, 6};
  const std::uint8_t type = D == 1 ? 3 : (D == 2 ? 9 : 12);  // VTK_LINE, VTK_QUAD, VTK_HEXAHEDRON
  const std::size_t n = domains.size();
  std::vector<double> points(3 * C * n, 0.0);
  std::vector<std::int64_t> connectivity(C * n), offsets(n);
  for (std::size_t p = 0; p < n; ++p) {
    for (int k = 0; k < C; ++k) {
      const std::size_t point = C * p + k;
      for (int a = 0; a < D; ++a) points[3 * point + a] = domains[p][D == 1 ? k : vtk_order[k]][a];
      connectivity[point] = static_cast<std::int64_t>(point);
    }
    offsets[p] = static_cast<std::int64_t>(C * (p + 1));
  }
  std::vector<std::uint8_t> types(n, type);
  std::vector<std::int64_t> ids(ps.id.begin(), ps.id.begin() + static_cast<std::ptrdiff_t>(n));
  std::vector<int> bodies(ps.body.begin(), ps.body.begin() + static_cast<std::ptrdiff_t>(n));
  AppendedData data;
  std::ostringstream piece;
  piece << "    <Piece NumberOfPoints=\"" << C * n << "\" NumberOfCells=\"" << n << "\">\n"
        << "      <CellData>\n"
        << data.array("id", "Int64", 1, ids) << data.array("body", "Int32", 1, bodies)
        << "      </CellData>\n"
        << "      <Points>\n"
        << data.array("Points", "Float64", 3, points) << "      </Points>\n"
        << "      <Cells>\n"
        << data.array("connectivity", "Int64", 1, connectivity) << data.array("offsets", "Int64", 1, offsets)
        << data.array("types", "UInt8", 1, types) << "      </Cells>\n"
        << "    </Piece>\n";
  return vtu_file(piece.str(), data);
}

void PvdCollection::add(double time, const std::string& dataset_file) {
  entries_.emplace_back(time, dataset_file);
  write();
}

void PvdCollection::restore(std::vector<std::pair<double, std::string>> entries) {
  entries_ = std::move(entries);
  if (!entries_.empty()) write();
}

void PvdCollection::set_static_part(std::string dataset_file) {
  static_part_ = std::move(dataset_file);
  if (!entries_.empty()) write();
}

void PvdCollection::set_companion_prefix(std::string prefix) {
  companion_prefix_ = std::move(prefix);
  if (!entries_.empty()) write();
}

namespace {

/// The text of the XML part of a .vtu (before the appended binary data).
std::string_view xml_head(const std::string& vtu) {
  const std::size_t end = vtu.find("<AppendedData");
  return std::string_view(vtu).substr(0, end == std::string::npos ? vtu.size() : end);
}

/// The <PDataArray .../> declarations of the DataArray elements inside `<section>`...`</section>`
/// of `head`, each with the DataArray's attributes except where its data lie (format, offset);
/// nullopt when the piece has no such section.
std::optional<std::string> declarations(std::string_view head, const std::string& section) {
  const std::string open = "<" + section + ">", close = "</" + section + ">";
  const std::size_t begin = head.find(open);
  if (begin == std::string_view::npos) return std::nullopt;
  const std::size_t end = head.find(close, begin);
  if (end == std::string_view::npos) throw std::invalid_argument("pvtu_file: a piece without " + close);
  const std::string_view body = head.substr(begin + open.size(), end - begin - open.size());
  std::string out;
  for (std::size_t at = body.find("<DataArray"); at != std::string_view::npos;
       at = body.find("<DataArray", at + 1)) {
    const std::size_t stop = body.find('>', at);
    if (stop == std::string_view::npos) throw std::invalid_argument("pvtu_file: an unterminated DataArray");
    std::string_view element = body.substr(at + 10, stop - at - 10);  // after "<DataArray"
    out += "      <PDataArray";
    // attributes: name="value", value without quotes (our writers' XML has no escapes)
    for (std::size_t k = 0;;) {
      const std::size_t eq = element.find("=\"", k);
      if (eq == std::string_view::npos) break;
      const std::size_t name_begin = element.find_last_of(" \t\n", eq) + 1;
      const std::size_t value_end = element.find('"', eq + 2);
      if (value_end == std::string_view::npos)
        throw std::invalid_argument("pvtu_file: an unquoted attribute");
      const std::string_view name = element.substr(name_begin, eq - name_begin);
      if (name != "format" && name != "offset") {
        out += ' ';
        out.append(element.substr(name_begin, value_end + 1 - name_begin));
      }
      k = value_end + 1;
    }
    out += "/>\n";
  }
  return out;
}

}  // namespace

std::string pvtu_file(const std::string& piece_vtu, const std::vector<std::string>& piece_files) {
  const std::string_view head = xml_head(piece_vtu);
  if (head.find("type=\"UnstructuredGrid\"") == std::string_view::npos)
    throw std::invalid_argument("pvtu_file: the piece is not a VTK UnstructuredGrid file");
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
         "<VTKFile type=\"PUnstructuredGrid\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n"
         "  <PUnstructuredGrid GhostLevel=\"0\">\n";
  for (const auto& [section, parallel] : {std::pair<const char*, const char*>{"PointData", "PPointData"},
                                          {"CellData", "PCellData"},
                                          {"Points", "PPoints"}})
    if (const auto arrays = declarations(head, section))
      out << "    <" << parallel << ">\n" << *arrays << "    </" << parallel << ">\n";
  for (const auto& file : piece_files) out << "    <Piece Source=\"" << file << "\"/>\n";
  out << "  </PUnstructuredGrid>\n</VTKFile>\n";
  return out.str();
}

void PvdCollection::write() const {
  if (!writes_) return;
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"1.0\">\n  <Collection>\n";
  out << std::setprecision(17);
  for (const auto& [t, file] : entries_) {
    out << "    <DataSet timestep=\"" << t << "\" part=\"0\" file=\"" << file << "\"/>\n";
    int part = 1;
    if (!static_part_.empty())
      out << "    <DataSet timestep=\"" << t << "\" part=\"" << part++ << "\" file=\"" << static_part_
          << "\"/>\n";
    if (!companion_prefix_.empty())
      out << "    <DataSet timestep=\"" << t << "\" part=\"" << part << "\" file=\"" << companion_prefix_
          << file.substr(file.find('_') + 1) << "\"/>\n";
  }
  out << "  </Collection>\n</VTKFile>\n";
  write_file_atomically(file_, out.str());
}

template std::string particles_vtu<1>(const ParticleSet<1>&, const std::vector<std::string>&, bool,
                                      const std::vector<std::string>&);
template std::string particles_vtu<2>(const ParticleSet<2>&, const std::vector<std::string>&, bool,
                                      const std::vector<std::string>&);
template std::string particles_vtu<3>(const ParticleSet<3>&, const std::vector<std::string>&, bool,
                                      const std::vector<std::string>&);
template std::string domains_vtu<1>(const std::vector<ParticleSet<1>::Corners>&, const ParticleSet<1>&);
template std::string domains_vtu<2>(const std::vector<ParticleSet<2>::Corners>&, const ParticleSet<2>&);
template std::string domains_vtu<3>(const std::vector<ParticleSet<3>::Corners>&, const ParticleSet<3>&);

}  // namespace matpoint
