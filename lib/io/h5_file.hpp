#pragma once
// Small RAII wrappers over the HDF5 C API (1.10+), used by the results writer,
// `compare` and the tests. Nothing outside io/ includes this header: the public
// results API (results_writer.hpp, results_compare.hpp) keeps HDF5 types out.
//
// Conventions: reals are stored as float64, ints as int32, counters as int64,
// strings as variable-length UTF-8 (h5py reads attributes back as str, the
// scalar /deck dataset as bytes). Arrays are row-major: a RowMatrix n x d is a
// dataset of shape (n, d); a Vector or std::vector is 1-D.
// Every failing HDF5 call becomes an iga::Error whose message names the object
// and carries HDF5's innermost error description. HDF5's automatic printing of
// error stacks is switched off inside H5ErrorSilencer scopes (every entry point
// of the results API opens one), so lib/ never prints.

#include "core/types.hpp"

#include <hdf5.h>

#include <span>
#include <string>
#include <vector>

namespace iga::io::h5 {

/// Switches HDF5's automatic error printing off for the current thread and
/// restores the previous handler on destruction.
class ErrorSilencer {
public:
    ErrorSilencer();
    ~ErrorSilencer();
    ErrorSilencer(const ErrorSilencer&) = delete;
    ErrorSilencer& operator=(const ErrorSilencer&) = delete;

private:
    H5E_auto2_t previous_func_ = nullptr;
    void* previous_data_ = nullptr;
};

/// HDF5's description of the innermost error on the current error stack
/// (e.g. "unable to open file: name = 'x.h5', errno = 2, ..."), or "" if none.
std::string last_error_description();

/// Throws iga::Error("<what>: <last_error_description()>"), a StorageError when the
/// description is of a write the file system refused (full disk, quota, I/O error).
[[noreturn]] void throw_error(const std::string& what);
/// The same with a description taken earlier (a later HDF5 call clears the stack).
[[noreturn]] void throw_described(const std::string& what, const std::string& description);

/// Before any other HDF5 call: no HDF5 shutdown at exit (see h5_file.cpp).
void no_shutdown_at_exit();

/// Owns one HDF5 identifier (file, group, dataset, attribute, dataspace,
/// datatype or property list) and closes it with the matching H5?close.
class Handle {
public:
    using Closer = herr_t (*)(hid_t);

    Handle() = default;
    /// Takes ownership of id; throws iga::Error("<what>: ...") if id < 0.
    Handle(hid_t id, Closer closer, const std::string& what);
    ~Handle() { reset(); }
    Handle(Handle&& other) noexcept;
    Handle& operator=(Handle&& other) noexcept;
    Handle(const Handle&) = delete;
    Handle& operator=(const Handle&) = delete;

    hid_t id() const { return id_; }
    bool valid() const { return id_ >= 0; }
    /// Closes now, ignoring errors (use close() where a failure must be reported).
    void reset() noexcept;
    /// Closes now; throws iga::Error if HDF5 reports a failure.
    void close();

private:
    hid_t id_ = H5I_INVALID_HID;
    Closer closer_ = nullptr;
};

// --- files, groups, links --------------------------------------------------

/// Creates (truncates) a file; its objects are closed with the file (strong close degree).
/// HDF5 1.8 file format, fixed 256 KB metadata cache (so a flush costs the same at every step).
Handle create_file(const std::string& path);
/// Opens an existing file read-only.
Handle open_file(const std::string& path);
/// Opens an existing file to add to it (a finished results file's copy, before it is renamed into place).
Handle open_file_for_update(const std::string& path);
Handle create_group(hid_t parent, const std::string& name);
/// Opens a group, dataset or named datatype by (relative or absolute) path.
Handle open_object(hid_t parent, const std::string& path);

/// True if every link along `path` (e.g. "steps/0001/contact") exists and resolves.
bool exists(hid_t location, const std::string& path);

enum class ObjectKind { group, dataset, other };
ObjectKind object_kind(hid_t object);

/// Names of the links in a group, in alphabetical order.
std::vector<std::string> link_names(hid_t group);
/// Names of the attributes of an object, in alphabetical order.
std::vector<std::string> attribute_names(hid_t object);

/// True if the two identifiers refer to the same object in the same file (hard links).
bool same_object(hid_t a, hid_t b);

/// Replaces (or creates) a hard link `link_name` in `location` pointing to `target`.
void replace_hard_link(hid_t location, const std::string& target, const std::string& link_name);

// --- writing ---------------------------------------------------------------

void write_dataset(hid_t location, const std::string& name, const RowMatrix& values);       ///< (rows, cols)
void write_dataset(hid_t location, const std::string& name, const Vector& values);          ///< (n,)
void write_dataset(hid_t location, const std::string& name, std::span<const double> values,
                   const std::vector<hsize_t>& dims);                                        ///< any shape
void write_dataset(hid_t location, const std::string& name, std::span<const int> values);   ///< (n,) int32
void write_dataset(hid_t location, const std::string& name, std::span<const int> values,
                   const std::vector<hsize_t>& dims);                                        ///< int32, any shape
void write_string_dataset(hid_t location, const std::string& name, const std::string& text);  ///< scalar
/// Variable-length string array of the given shape (row-major, product(dims) == values.size()).
void write_string_dataset(hid_t location, const std::string& name, const std::vector<std::string>& values,
                          const std::vector<hsize_t>& dims);

void write_attribute(hid_t object, const std::string& name, double value);
void write_attribute(hid_t object, const std::string& name, int value);
void write_attribute(hid_t object, const std::string& name, long long value);
void write_attribute(hid_t object, const std::string& name, const std::string& value);
void write_attribute(hid_t object, const std::string& name, std::span<const double> values);  ///< 1-D

// --- reading ---------------------------------------------------------------

/// The contents of a dataset or attribute, converted to one of three value types.
struct Array {
    enum class Type { real, integer, string, other };
    Type type = Type::other;
    std::vector<hsize_t> dims;         ///< empty for a scalar
    std::vector<double> reals;         ///< Type::real, row-major
    std::vector<long long> integers;   ///< Type::integer, row-major
    std::vector<std::string> strings;  ///< Type::string, row-major
    std::string type_description;      ///< e.g. "float64", "int32", "string", "compound"

    std::size_t n_values() const;
};

Array read_dataset(hid_t location, const std::string& path);
Array read_attribute(hid_t object, const std::string& name);

/// "(3, 2)", "()" for a scalar.
std::string format_dims(const std::vector<hsize_t>& dims);

}  // namespace iga::io::h5
