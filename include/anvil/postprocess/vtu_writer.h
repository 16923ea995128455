#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace anvil
{
  /**
   * One piece of an unstructured grid as VTK's XML format holds it: points,
   * cells and point data in the types written (@p Float: float is Float32
   * like deal.II's patches, double Float64; Int32 cells). Filled by an
   * output, written by write_vtu_raw().
   */
  template <typename Float>
  struct BasicVtuPiece
  {
    std::vector<Float>         points;       // x, y, z per point
    std::vector<std::int32_t>  connectivity; // the cells' points, VTK's vertex order
    std::vector<std::int32_t>  offsets;      // per cell, the end of its points in connectivity
    std::vector<std::uint8_t>  types;        // per cell, VTK's cell type
    struct Array
    {
      std::string        name;
      unsigned int       components = 1;
      std::vector<Float> values; // components per point
    };
    std::vector<Array> point_data;

    std::size_t n_points() const { return points.size() / 3; }
  };
  using VtuPiece = BasicVtuPiece<float>;

  /**
   * Writes @p piece to @p filename with its arrays appended raw
   * (`<AppendedData encoding="raw">`, each block its UInt32 byte count then
   * the bytes): no compression and no base64, so a write costs about a
   * memory copy; VTK and ParaView read it. Files are about 3 times the
   * zlib ones.
   */
  template <typename Float>
  void write_vtu_raw(const BasicVtuPiece<Float> &piece, const std::string &filename);

  /// A point array's name and components per point.
  struct VtuArray
  {
    std::string  name;
    unsigned int components = 1;
  };

  /**
   * write_vtu_raw()'s file with the point arrays made one at a time:
   * @p fill(i, values) puts array i's values (@p arrays[i].components per
   * point) in values, which is written and then filled again with the next
   * array, so the arrays are never all held (the header's offsets follow
   * from the sizes). @p mesh gives the points and cells; its point_data is
   * not read. The same bytes as write_vtu_raw() of the piece holding the arrays.
   */
  template <typename Float>
  void write_vtu_raw(const BasicVtuPiece<Float> &mesh, const std::vector<VtuArray> &arrays,
                     const std::function<void(std::size_t, std::vector<Float> &)> &fill,
                     const std::string                                               &filename);

  /// The .pvtu record naming @p pieces (relative to it), with @p piece's array names.
  template <typename Float>
  void write_pvtu_record(const BasicVtuPiece<Float> &piece, const std::vector<std::string> &pieces,
                         const std::string &filename);

  /// The .pvtu record naming @p pieces, with the point arrays @p arrays (of type @p Float).
  template <typename Float>
  void write_pvtu_record(const std::vector<VtuArray> &arrays, const std::vector<std::string> &pieces,
                         const std::string &filename);
} // namespace anvil
