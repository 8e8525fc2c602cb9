#include "AtomicFile.H"

#include <atomic>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include <fcntl.h>
#include <unistd.h>

namespace fs = std::filesystem;

namespace iceDEM
{

namespace
{

std::runtime_error writeError(const std::string& path, const std::string& why)
{
    return std::runtime_error("cannot write file '" + path + "': " + why);
}

fs::path folderOf(const std::string& path)
{
    const fs::path parent = fs::path(path).parent_path();
    return parent.empty() ? fs::path(".") : parent;
}

// Unique within the process (counter) and between processes (pid), hidden, same folder.
std::string temporaryPathFor(const std::string& path)
{
    static std::atomic<unsigned long> counter{0};
    const fs::path target(path);
    const std::string name =
        "." + target.filename().string() + ".tmp." + std::to_string(::getpid())
      + "." + std::to_string(counter++);
    return (folderOf(path) / name).string();
}

void createParentFolders(const std::string& path)
{
    std::error_code ec;
    fs::create_directories(folderOf(path), ec);
    if (ec)
    {
        throw writeError(path, "cannot create folder '" + folderOf(path).string() + "': "
                         + ec.message());
    }
}

void syncToDisk(const std::string& fileOrFolder, const std::string& path, bool required)
{
    const int fd = ::open(fileOrFolder.c_str(), O_RDONLY);
    if (fd < 0)
    {
        if (required)
        {
            throw writeError(path, "cannot reopen '" + fileOrFolder + "': "
                             + std::strerror(errno));
        }
        return;
    }
    const int syncResult = ::fsync(fd);
    const int syncErrno = errno;
    ::close(fd);
    if (syncResult != 0 && required)
    {
        throw writeError(path, "fsync of '" + fileOrFolder + "' failed: "
                         + std::strerror(syncErrno));
    }
}

// Flush the finished temporary file to disk and rename it over the target.
void commit(const std::string& tempPath, const std::string& path)
{
    syncToDisk(tempPath, path, true);
    std::error_code ec;
    fs::rename(tempPath, path, ec);
    if (ec)
    {
        throw writeError(path, "cannot rename '" + tempPath + "' to it: " + ec.message());
    }
    // Make the rename itself durable; not all file systems allow syncing a folder.
    syncToDisk(folderOf(path).string(), path, false);
}

void removeQuietly(const std::string& tempPath)
{
    std::error_code ec;
    fs::remove(tempPath, ec);
}

} // namespace


void writeAtomically
(
    const std::string& path,
    const std::function<void(const std::string& tempPath)>& produce
)
{
    if (path.empty())
    {
        throw std::runtime_error("cannot write file: empty path");
    }
    createParentFolders(path);
    const std::string tempPath = temporaryPathFor(path);
    try
    {
        produce(tempPath);
        if (!fs::is_regular_file(tempPath))
        {
            throw writeError(path, "the writer produced no file at '" + tempPath + "'");
        }
        commit(tempPath, path);
    }
    catch (...)
    {
        removeQuietly(tempPath);
        throw;
    }
}


void writeStreamAtomically
(
    const std::string& path,
    const std::function<void(std::ostream&)>& produce
)
{
    writeAtomically
    (
        path,
        [&](const std::string& tempPath)
        {
            std::ofstream out(tempPath, std::ios::out | std::ios::trunc | std::ios::binary);
            if (!out)
            {
                throw writeError(path, "cannot open temporary file '" + tempPath + "': "
                                 + std::strerror(errno));
            }
            produce(out);
            out.close();
            if (out.fail())
            {
                throw writeError(path, "write to temporary file '" + tempPath + "' failed");
            }
        }
    );
}


void writeFileAtomically(const std::string& path, const std::string& content)
{
    writeStreamAtomically(path, [&](std::ostream& out) { out << content; });
}

} // namespace iceDEM
