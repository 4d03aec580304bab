// A string attribute read with HDF5 itself, as other readers see it: variable-length (granjet's
// units) or fixed-length (H5MD's own).
#pragma once

#include <hdf5.h>

#include <string>

namespace granjet::testing {

inline std::string string_attribute(hid_t file, const std::string& object, const char* name) {
  const hid_t a = H5Aopen_by_name(file, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT);
  const hid_t type = H5Aget_type(a);
  std::string value;
  if (H5Tis_variable_str(type) > 0) {
    char* text = nullptr;
    H5Aread(a, type, &text);
    value = text;
    H5free_memory(text);
  } else {
    value.resize(H5Tget_size(type));
    H5Aread(a, type, value.data());
    value.resize(value.find('\0'));
  }
  H5Tclose(type);
  H5Aclose(a);
  return value;
}

}  // namespace granjet::testing
