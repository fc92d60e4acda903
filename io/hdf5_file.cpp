#include "io/hdf5_file.hpp"

#include <hdf5_hl.h>

#include <stdexcept>
#include <utility>

namespace mpile {

namespace {

// Rows per chunk of an extendible series.
constexpr hsize_t chunk_rows = 4096;

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error("HDF5: " + what);
}

hid_t check(hid_t id, const std::string& what) {
  if (id < 0) {
    fail(what);
  }
  return id;
}

// The library's own error printing is replaced by exceptions with the object's path. Files are
// closed where they are used, with their failures reported; the library does not close at exit
// what it could not close then (HDF5 1.10 crashed closing a file whose last write had failed).
struct SilenceHdf5Errors {
  SilenceHdf5Errors() {
    H5dont_atexit();
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
};
const SilenceHdf5Errors silence;

// Variable-length UTF-8 strings: h5py reads them as str.
Hdf5Handle string_type() {
  Hdf5Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  return type;
}

} // namespace

Hdf5Handle::Hdf5Handle(Hdf5Handle&& other) noexcept
    : id_(std::exchange(other.id_, -1)), close_(other.close_) {}

Hdf5Handle& Hdf5Handle::operator=(Hdf5Handle&& other) noexcept {
  if (this != &other) {
    if (id_ >= 0 && close_ != nullptr) {
      close_(id_);
    }
    id_ = std::exchange(other.id_, -1);
    close_ = other.close_;
  }
  return *this;
}

bool Hdf5Handle::close() {
  const hid_t id = std::exchange(id_, -1);
  return id < 0 || close_ == nullptr || close_(id) >= 0;
}

Hdf5Handle::~Hdf5Handle() {
  if (id_ >= 0 && close_ != nullptr) {
    close_(id_);
  }
}

Hdf5File::Hdf5File(const std::string& path, Mode mode) : path_(path) {
  Hdf5Handle access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  H5Pset_file_locking(access.get(), false, true);
  hid_t id = -1;
  if (mode == Mode::create) {
    id = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, access.get());
  } else {
    id = H5Fopen(path.c_str(), mode == Mode::read ? H5F_ACC_RDONLY : H5F_ACC_RDWR, access.get());
  }
  if (id < 0) {
    fail("cannot " + std::string(mode == Mode::create ? "create " : "open ") + path);
  }
  file_ = Hdf5Handle(id, H5Fclose);
}

void Hdf5File::close() {
  if (!file_.close()) {
    fail("cannot finish writing " + path_ +
         " (no space left on its file system, or a file-size "
         "limit)");
  }
}

bool Hdf5File::exists(const std::string& object) const {
  // Check each level, since H5Lexists fails when a parent is missing.
  std::size_t position = 1;
  while (position <= object.size()) {
    const std::size_t next = object.find('/', position);
    const std::string prefix = object.substr(0, next);
    if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) {
      return false;
    }
    if (next == std::string::npos) {
      break;
    }
    position = next + 1;
  }
  return true;
}

Hdf5Handle Hdf5File::parent_group(const std::string& object) {
  const std::size_t slash = object.rfind('/');
  std::string parent = slash == 0 || slash == std::string::npos ? "/" : object.substr(0, slash);
  std::size_t position = 1;
  while (position < parent.size()) {
    const std::size_t next = parent.find('/', position);
    const std::string prefix = parent.substr(0, next);
    if (H5Lexists(file_.get(), prefix.c_str(), H5P_DEFAULT) <= 0) {
      Hdf5Handle group(
          check(H5Gcreate2(file_.get(), prefix.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
                "cannot create group " + prefix + " in " + path_),
          H5Gclose);
    }
    if (next == std::string::npos) {
      break;
    }
    position = next + 1;
  }
  return Hdf5Handle(check(H5Gopen2(file_.get(), parent.c_str(), H5P_DEFAULT),
                          "cannot open group " + parent + " in " + path_),
                    H5Gclose);
}

void Hdf5File::write_raw(const std::string& dataset, hid_t type, const void* data,
                         std::size_t count, std::vector<hsize_t> dims) {
  if (dims.empty()) {
    dims = {static_cast<hsize_t>(count)};
  }
  parent_group(dataset);
  if (exists(dataset)) {
    H5Ldelete(file_.get(), dataset.c_str(), H5P_DEFAULT);
  }
  Hdf5Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose);
  Hdf5Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  if (count > 0) {
    // Chunked, so that every chunk carries a Fletcher32 checksum: a checkpoint or history damaged
    // on disk is refused when read instead of read back as other numbers. Large arrays are also
    // compressed (particle arrays compress well and keep checkpoints small); the checksum goes
    // last, over the bytes as stored.
    std::vector<hsize_t> chunk = dims;
    chunk[0] = std::min<hsize_t>(dims[0], 65536);
    H5Pset_chunk(properties.get(), static_cast<int>(chunk.size()), chunk.data());
    if (count >= 1024) {
      H5Pset_deflate(properties.get(), 1);
    }
    H5Pset_fletcher32(properties.get());
  }
  Hdf5Handle set(check(H5Dcreate2(file_.get(), dataset.c_str(), type, space.get(), H5P_DEFAULT,
                                  properties.get(), H5P_DEFAULT),
                       "cannot create " + dataset + " in " + path_),
                 H5Dclose);
  if (count > 0 && H5Dwrite(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    fail("cannot write " + dataset + " in " + path_);
  }
}

void Hdf5File::write(const std::string& dataset, std::span<const double> values,
                     const std::string& unit, std::vector<hsize_t> dims) {
  write_raw(dataset, H5T_NATIVE_DOUBLE, values.data(), values.size(), std::move(dims));
  set_attribute(dataset, "units", unit);
}

void Hdf5File::write(const std::string& dataset, std::span<const std::int32_t> values,
                     std::vector<hsize_t> dims) {
  write_raw(dataset, H5T_NATIVE_INT32, values.data(), values.size(), std::move(dims));
}

void Hdf5File::write(const std::string& dataset, std::span<const std::uint16_t> values) {
  write_raw(dataset, H5T_NATIVE_UINT16, values.data(), values.size(), {});
}

std::size_t Hdf5File::element_count(const std::string& dataset) const {
  Hdf5Handle set(check(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT),
                       "no dataset " + dataset + " in " + path_),
                 H5Dclose);
  Hdf5Handle space(H5Dget_space(set.get()), H5Sclose);
  return static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.get()));
}

void Hdf5File::read_raw(const std::string& dataset, hid_t type, void* data,
                        std::size_t count) const {
  Hdf5Handle set(check(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT),
                       "no dataset " + dataset + " in " + path_),
                 H5Dclose);
  if (count > 0 && H5Dread(set.get(), type, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0) {
    fail("cannot read " + dataset + " in " + path_);
  }
}

std::vector<double> Hdf5File::read_doubles(const std::string& dataset) const {
  std::vector<double> values(element_count(dataset));
  read_raw(dataset, H5T_NATIVE_DOUBLE, values.data(), values.size());
  return values;
}

std::vector<std::int32_t> Hdf5File::read_int32(const std::string& dataset) const {
  std::vector<std::int32_t> values(element_count(dataset));
  read_raw(dataset, H5T_NATIVE_INT32, values.data(), values.size());
  return values;
}

std::vector<std::uint16_t> Hdf5File::read_uint16(const std::string& dataset) const {
  std::vector<std::uint16_t> values(element_count(dataset));
  read_raw(dataset, H5T_NATIVE_UINT16, values.data(), values.size());
  return values;
}

void Hdf5File::set_attribute(const std::string& object, const std::string& name,
                             const std::string& value) {
  if (H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0) {
    H5Adelete_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT);
  }
  Hdf5Handle type = string_type();
  Hdf5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Hdf5Handle attribute(
      check(H5Acreate_by_name(file_.get(), object.c_str(), name.c_str(), type.get(), space.get(),
                              H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
            "cannot set attribute " + name + " of " + object + " in " + path_),
      H5Aclose);
  const char* text = value.c_str();
  H5Awrite(attribute.get(), type.get(), &text);
}

void Hdf5File::set_attribute(const std::string& object, const std::string& name, double value) {
  if (H5Aexists_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT) > 0) {
    H5Adelete_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT);
  }
  Hdf5Handle space(H5Screate(H5S_SCALAR), H5Sclose);
  Hdf5Handle attribute(
      check(H5Acreate_by_name(file_.get(), object.c_str(), name.c_str(), H5T_NATIVE_DOUBLE,
                              space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
            "cannot set attribute " + name + " of " + object + " in " + path_),
      H5Aclose);
  H5Awrite(attribute.get(), H5T_NATIVE_DOUBLE, &value);
}

std::string Hdf5File::string_attribute(const std::string& object, const std::string& name) const {
  Hdf5Handle attribute(
      check(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
            "no attribute " + name + " on " + object + " in " + path_),
      H5Aclose);
  Hdf5Handle type = string_type();
  char* text = nullptr;
  if (H5Aread(attribute.get(), type.get(), &text) < 0 || text == nullptr) {
    fail("cannot read attribute " + name + " of " + object + " in " + path_);
  }
  std::string value(text);
  H5free_memory(text);
  return value;
}

double Hdf5File::number_attribute(const std::string& object, const std::string& name) const {
  Hdf5Handle attribute(
      check(H5Aopen_by_name(file_.get(), object.c_str(), name.c_str(), H5P_DEFAULT, H5P_DEFAULT),
            "no attribute " + name + " on " + object + " in " + path_),
      H5Aclose);
  double value = 0.0;
  H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value);
  return value;
}

void Hdf5File::flush() {
  H5Fflush(file_.get(), H5F_SCOPE_GLOBAL);
}

void Hdf5File::make_dimension_scale(const std::string& dataset, const std::string& name) {
  Hdf5Handle set(check(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT),
                       "no dataset " + dataset + " in " + path_),
                 H5Dclose);
  if (H5DSset_scale(set.get(), name.c_str()) < 0) {
    fail("cannot make " + dataset + " a dimension scale in " + path_);
  }
}

void Hdf5File::attach_dimension_scale(const std::string& dataset, const std::string& scale) {
  Hdf5Handle set(check(H5Dopen2(file_.get(), dataset.c_str(), H5P_DEFAULT),
                       "no dataset " + dataset + " in " + path_),
                 H5Dclose);
  Hdf5Handle scale_set(check(H5Dopen2(file_.get(), scale.c_str(), H5P_DEFAULT),
                             "no dataset " + scale + " in " + path_),
                       H5Dclose);
  if (H5DSattach_scale(set.get(), scale_set.get(), 0) < 0) {
    fail("cannot attach the dimension scale " + scale + " to " + dataset + " in " + path_);
  }
}

Hdf5Series::Hdf5Series(Hdf5File& file, const std::string& dataset, const std::string& unit,
                       Stored stored)
    : dataset_(dataset) {
  file.parent_group(dataset);
  const hsize_t initial = 0, unlimited = H5S_UNLIMITED, chunk = chunk_rows;
  Hdf5Handle space(H5Screate_simple(1, &initial, &unlimited), H5Sclose);
  Hdf5Handle properties(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_chunk(properties.get(), 1, &chunk);
  // A checksum per chunk: history data damaged on disk is refused when read (here, by h5py and by
  // any HDF5 reader) instead of read back as other numbers.
  H5Pset_fletcher32(properties.get());
  const hid_t type = stored == Stored::integer ? H5T_STD_I64LE : H5T_NATIVE_DOUBLE;
  Hdf5Handle set(check(H5Dcreate2(file.id(), dataset.c_str(), type, space.get(), H5P_DEFAULT,
                                  properties.get(), H5P_DEFAULT),
                       "cannot create " + dataset + " in " + file.path()),
                 H5Dclose);
  file.set_attribute(dataset, "units", unit);
}

Hdf5Series::Hdf5Series(Hdf5File& file, const std::string& dataset, std::size_t rows)
    : dataset_(dataset) {
  Hdf5Handle set(check(H5Dopen2(file.id(), dataset.c_str(), H5P_DEFAULT),
                       "no dataset " + dataset + " in " + file.path()),
                 H5Dclose);
  // Fewer rows in the file than asked for would be filled with zeros: refuse instead.
  Hdf5Handle space(H5Dget_space(set.get()), H5Sclose);
  hsize_t held = 0;
  H5Sget_simple_extent_dims(space.get(), &held, nullptr);
  if (held < rows) {
    fail(file.path() + ": " + dataset + " holds " + std::to_string(held) + " rows, not the " +
         std::to_string(rows) + " the checkpoint counts (the history was not written up to it)");
  }
  written_ = static_cast<hsize_t>(rows);
  if (H5Dset_extent(set.get(), &written_) < 0) {
    fail("cannot resize " + dataset + " in " + file.path());
  }
}

std::size_t Hdf5Series::growth_bound() const {
  const auto chunks = [](hsize_t rows) { return (rows + chunk_rows - 1) / chunk_rows; };
  const hsize_t new_chunks = chunks(written_ + buffer_.size()) - chunks(written_);
  // A chunk index node is about 2 KiB; a split makes a node and at most a new root.
  return static_cast<std::size_t>(new_chunks * (chunk_rows * sizeof(double) + 8192));
}

void Hdf5Series::flush(Hdf5File& file) {
  if (buffer_.empty()) {
    return;
  }
  Hdf5Handle set(check(H5Dopen2(file.id(), dataset_.c_str(), H5P_DEFAULT),
                       "no dataset " + dataset_ + " in " + file.path()),
                 H5Dclose);
  const hsize_t total = written_ + buffer_.size();
  const hsize_t count = buffer_.size();
  if (H5Dset_extent(set.get(), &total) < 0) {
    fail("cannot extend " + dataset_ + " in " + file.path());
  }
  Hdf5Handle file_space(H5Dget_space(set.get()), H5Sclose);
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, &written_, nullptr, &count, nullptr);
  Hdf5Handle memory_space(H5Screate_simple(1, &count, nullptr), H5Sclose);
  if (H5Dwrite(set.get(), H5T_NATIVE_DOUBLE, memory_space.get(), file_space.get(), H5P_DEFAULT,
               buffer_.data()) < 0) {
    fail("cannot append to " + dataset_ + " in " + file.path());
  }
  // The chunk is written when the dataset closes: a failure there is a failure to append.
  if (!set.close()) {
    fail("cannot append to " + dataset_ + " in " + file.path());
  }
  written_ = total;
  buffer_.clear();
}

} // namespace mpile
