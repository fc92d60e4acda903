#pragma once

// A small RAII layer over the HDF5 C library: files, groups made on demand, whole arrays with a
// units attribute, string and number attributes, dimension scales, and extendible 1-D series for
// histories. Files are opened without HDF5's file locks: mpile's output directory has its own lock
// (one run per directory), and a reader (h5py, HDFView) holding a history open must not stop the
// run that appends to it.

#include <hdf5.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace mpile {

/// An HDF5 identifier closed by its destructor.
class Hdf5Handle {
public:
  Hdf5Handle() = default;
  Hdf5Handle(hid_t id, herr_t (*closer)(hid_t)) : id_(id), close_(closer) {}
  Hdf5Handle(Hdf5Handle&& other) noexcept;
  Hdf5Handle& operator=(Hdf5Handle&& other) noexcept;
  Hdf5Handle(const Hdf5Handle&) = delete;
  Hdf5Handle& operator=(const Hdf5Handle&) = delete;
  ~Hdf5Handle();
  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Closes now; false when the library could not (a write it had deferred failed).
  bool close();

private:
  hid_t id_ = -1;
  herr_t (*close_)(hid_t) = nullptr;
};

class Hdf5File {
public:
  enum class Mode { create, read, append };
  Hdf5File(const std::string& path, Mode mode);

  const std::string& path() const { return path_; }
  hid_t id() const { return file_.get(); }
  /// Closes the file, writing what the library still holds; throws when that fails (a full disk
  /// or a file-size limit shows here: the destructor cannot report it).
  void close();
  bool exists(const std::string& object) const;

  /// Whole arrays (row-major, dims as given; one dimension when dims is empty).
  void write(const std::string& dataset, std::span<const double> values, const std::string& unit,
             std::vector<hsize_t> dims = {});
  void write(const std::string& dataset, std::span<const std::int32_t> values,
             std::vector<hsize_t> dims = {});
  void write(const std::string& dataset, std::span<const std::uint16_t> values);
  std::vector<double> read_doubles(const std::string& dataset) const;
  std::vector<std::int32_t> read_int32(const std::string& dataset) const;
  std::vector<std::uint16_t> read_uint16(const std::string& dataset) const;

  void set_attribute(const std::string& object, const std::string& name, const std::string& value);
  void set_attribute(const std::string& object, const std::string& name, double value);
  std::string string_attribute(const std::string& object, const std::string& name) const;
  double number_attribute(const std::string& object, const std::string& name) const;

  void flush();
  /// Makes a 1-D dataset a dimension scale called `name`, and attaches it to the first dimension
  /// of another dataset, so netCDF readers (xarray) see them share a dimension.
  void make_dimension_scale(const std::string& dataset, const std::string& name);
  void attach_dimension_scale(const std::string& dataset, const std::string& scale);
  /// Opens (or makes, with its parents) the group holding an object path like /a/b/c.
  Hdf5Handle parent_group(const std::string& object);

private:
  void write_raw(const std::string& dataset, hid_t type, const void* data, std::size_t count,
                 std::vector<hsize_t> dims);
  void read_raw(const std::string& dataset, hid_t type, void* data, std::size_t count) const;
  std::size_t element_count(const std::string& dataset) const;

  std::string path_;
  Hdf5Handle file_;
};

/// A 1-D dataset that grows: values are buffered and written in chunks on flush. Stored as doubles,
/// or as 64-bit integers for counts and indices (the values given are then whole numbers, which
/// HDF5 converts exactly below 2^53). It holds no HDF5 handle between flushes, so the file it
/// lives in can be closed between them.
class Hdf5Series {
public:
  enum class Stored { real, integer };
  Hdf5Series(Hdf5File& file, const std::string& dataset, const std::string& unit,
             Stored stored = Stored::real);
  /// Opens an existing series and keeps its first `rows` values (for a restart).
  Hdf5Series(Hdf5File& file, const std::string& dataset, std::size_t rows);
  void append(double value) { buffer_.push_back(value); }
  /// Appends the buffered values to the dataset in `file` (open for writing).
  void flush(Hdf5File& file);
  /// At most the bytes the file grows by when the buffered values are flushed: the chunks they
  /// begin, and room for the chunk index to split.
  std::size_t growth_bound() const;
  std::size_t size() const { return written_ + buffer_.size(); }
  const std::string& dataset() const { return dataset_; }

private:
  std::string dataset_;
  std::vector<double> buffer_;
  hsize_t written_ = 0;
};

} // namespace mpile
