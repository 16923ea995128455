// VTK XML unstructured grids with raw appended data (VTK's file-formats
// document, "Appended data"): offsets count bytes from the character after
// the '_' that opens the appended section.
#include <anvil/postprocess/vtu_writer.h>

#include <cstring>
#include <fstream>
#include <stdexcept>

namespace anvil
{
  namespace
  {
    const char *byte_order()
    {
      const std::uint16_t one = 1;
      unsigned char       first;
      std::memcpy(&first, &one, 1);
      return first == 1 ? "LittleEndian" : "BigEndian";
    }

    template <typename T>
    std::uint64_t block_size(const std::vector<T> &v)
    {
      return sizeof(std::uint32_t) + v.size() * sizeof(T);
    }

    template <typename T>
    void write_block(std::ofstream &out, const std::vector<T> &v)
    {
      const std::uint64_t bytes = v.size() * sizeof(T);
      if (bytes > 0xffffffffu)
        throw std::runtime_error("write_vtu_raw: an array of more than 4 GB");
      const std::uint32_t header = static_cast<std::uint32_t>(bytes);
      out.write(reinterpret_cast<const char *>(&header), sizeof header);
      out.write(reinterpret_cast<const char *>(v.data()), static_cast<std::streamsize>(bytes));
    }
  } // namespace

  template <typename Float>
  void write_vtu_raw(const BasicVtuPiece<Float> &mesh, const std::vector<VtuArray> &arrays,
                     const std::function<void(std::size_t, std::vector<Float> &)> &fill,
                     const std::string                                               &filename)
  {
    const char *type = sizeof(Float) == 4 ? "Float32" : "Float64";
    const std::size_t n_points = mesh.n_points(), n_cells = mesh.types.size();
    std::ofstream out(filename, std::ios::binary);
    if (!out)
      throw std::runtime_error("cannot write " + filename);
    std::uint64_t offset = 0;
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\" "
           "byte_order=\""
        << byte_order() << "\" header_type=\"UInt32\">\n<UnstructuredGrid>\n<Piece NumberOfPoints=\""
        << n_points << "\" NumberOfCells=\"" << n_cells << "\">\n<PointData>\n";
    for (const auto &a : arrays)
      {
        out << "<DataArray type=\"" << type << "\" Name=\"" << a.name << "\"";
        if (a.components > 1)
          out << " NumberOfComponents=\"" << a.components << "\"";
        out << " format=\"appended\" offset=\"" << offset << "\"/>\n";
        offset += sizeof(std::uint32_t) + n_points * a.components * sizeof(Float);
      }
    out << "</PointData>\n<Points>\n<DataArray type=\"" << type
        << "\" NumberOfComponents=\"3\" format=\"appended\" offset=\""
        << offset << "\"/>\n</Points>\n<Cells>\n";
    offset += block_size(mesh.points);
    out << "<DataArray type=\"Int32\" Name=\"connectivity\" format=\"appended\" offset=\""
        << offset << "\"/>\n";
    offset += block_size(mesh.connectivity);
    out << "<DataArray type=\"Int32\" Name=\"offsets\" format=\"appended\" offset=\"" << offset
        << "\"/>\n";
    offset += block_size(mesh.offsets);
    out << "<DataArray type=\"UInt8\" Name=\"types\" format=\"appended\" offset=\"" << offset
        << "\"/>\n</Cells>\n</Piece>\n</UnstructuredGrid>\n<AppendedData encoding=\"raw\">\n_";
    std::vector<Float> values;
    for (std::size_t i = 0; i < arrays.size(); ++i)
      {
        fill(i, values);
        // The header promised this size: a shorter or longer block would
        // shift every later offset.
        if (values.size() != n_points * arrays[i].components)
          throw std::logic_error("write_vtu_raw: array " + arrays[i].name + " has " +
                                 std::to_string(values.size()) + " values for " +
                                 std::to_string(n_points) + " points");
        write_block(out, values);
      }
    std::vector<Float>().swap(values);
    write_block(out, mesh.points);
    write_block(out, mesh.connectivity);
    write_block(out, mesh.offsets);
    write_block(out, mesh.types);
    out << "\n</AppendedData>\n</VTKFile>\n";
    if (!out)
      throw std::runtime_error("cannot write " + filename);
  }

  template <typename Float>
  void write_vtu_raw(const BasicVtuPiece<Float> &piece, const std::string &filename)
  {
    std::vector<VtuArray> arrays;
    for (const auto &a : piece.point_data)
      arrays.push_back({a.name, a.components});
    // The piece's arrays as they are (one copy at a time).
    write_vtu_raw<Float>(
      piece, arrays,
      [&](const std::size_t i, std::vector<Float> &values) { values = piece.point_data[i].values; },
      filename);
  }

  template <typename Float>
  void write_pvtu_record(const std::vector<VtuArray> &arrays, const std::vector<std::string> &pieces,
                         const std::string &filename)
  {
    const char *type = sizeof(Float) == 4 ? "Float32" : "Float64";
    std::ofstream out(filename);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\" "
           "byte_order=\""
        << byte_order() << "\" header_type=\"UInt32\">\n  <PUnstructuredGrid GhostLevel=\"0\">\n"
        << "    <PPointData>\n";
    for (const auto &a : arrays)
      {
        out << "    <PDataArray type=\"" << type << "\" Name=\"" << a.name << "\"";
        if (a.components > 1)
          out << " NumberOfComponents=\"" << a.components << "\"";
        out << "/>\n";
      }
    out << "    </PPointData>\n    <PPoints>\n      <PDataArray type=\"" << type
        << "\" NumberOfComponents=\"3\"/>\n    </PPoints>\n";
    for (const auto &p : pieces)
      out << "    <Piece Source=\"" << p << "\"/>\n";
    out << "  </PUnstructuredGrid>\n</VTKFile>\n";
    if (!out)
      throw std::runtime_error("cannot write " + filename);
  }

  template <typename Float>
  void write_pvtu_record(const BasicVtuPiece<Float> &piece, const std::vector<std::string> &pieces,
                         const std::string &filename)
  {
    std::vector<VtuArray> arrays;
    for (const auto &a : piece.point_data)
      arrays.push_back({a.name, a.components});
    write_pvtu_record<Float>(arrays, pieces, filename);
  }

  template void write_vtu_raw(const BasicVtuPiece<float> &, const std::string &);
  template void write_vtu_raw(const BasicVtuPiece<double> &, const std::string &);
  template void write_pvtu_record(const BasicVtuPiece<float> &, const std::vector<std::string> &,
                                  const std::string &);
  template void write_pvtu_record(const BasicVtuPiece<double> &, const std::vector<std::string> &,
                                  const std::string &);
  template void write_pvtu_record<float>(const std::vector<VtuArray> &, const std::vector<std::string> &,
                                         const std::string &);
  template void write_vtu_raw(const BasicVtuPiece<float> &, const std::vector<VtuArray> &,
                              const std::function<void(std::size_t, std::vector<float> &)> &,
                              const std::string &);
} // namespace anvil
