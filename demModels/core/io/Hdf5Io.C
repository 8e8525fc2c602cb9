#include "Hdf5Io.H"

namespace iceDEM
{

std::string hdf5Failure(const std::string& path, const std::string& what)
{
    return "HDF5 file '" + path + "': " + what;
}


void writeDataset
(
    hid_t group,
    const char* name,
    hid_t fileType,
    hid_t memoryType,
    const void* data,
    hsize_t n,
    const std::string& path
)
{
    H5Id space(H5Screate_simple(1, &n, nullptr), H5Sclose,
               hdf5Failure(path, std::string("cannot create dataspace for ") + name));
    H5Id dataset
    (
        H5Dcreate2(group, name, fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        H5Dclose,
        hdf5Failure(path, std::string("cannot create dataset ") + name)
    );
    if (n > 0
     && H5Dwrite(dataset.get(), memoryType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    {
        throw std::runtime_error(hdf5Failure(path, std::string("cannot write dataset ") + name));
    }
}


std::string readStringAttributeOrEmpty(hid_t object, const char* name, const std::string& path)
{
    if (H5Aexists(object, name) <= 0)
    {
        return "";
    }
    const std::string context = hdf5Failure(path, std::string("cannot read attribute ") + name);
    H5Id attribute(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, context);
    H5Id type(H5Aget_type(attribute.get()), H5Tclose, context);
    if (H5Tget_class(type.get()) != H5T_STRING || H5Tis_variable_str(type.get()) > 0)
    {
        throw std::runtime_error(context + " (not a fixed-length string)");
    }
    std::string value(H5Tget_size(type.get()), '\0');
    if (H5Aread(attribute.get(), type.get(), value.data()) < 0)
    {
        throw std::runtime_error(context);
    }
    return value.substr(0, value.find('\0'));
}


void writeStringAttribute
(
    hid_t object,
    const char* name,
    const std::string& value,
    const std::string& path
)
{
    const std::string context = hdf5Failure(path, std::string("cannot write attribute ") + name);
    H5Id type(H5Tcopy(H5T_C_S1), H5Tclose, context);
    if (H5Tset_size(type.get(), value.size()) < 0
     || H5Tset_strpad(type.get(), H5T_STR_NULLPAD) < 0)
    {
        throw std::runtime_error(context);
    }
    H5Id space(H5Screate(H5S_SCALAR), H5Sclose, context);
    H5Id attribute
    (
        H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
        H5Aclose,
        context
    );
    if (H5Awrite(attribute.get(), type.get(), value.data()) < 0)
    {
        throw std::runtime_error(context);
    }
}


} // namespace iceDEM
