#include "AtomicFile.H"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

using namespace std::string_literals;

namespace fs = std::filesystem;
using namespace iceDEM;

namespace
{

class AtomicFile : public ::testing::Test
{
protected:
    void SetUp() override
    {
        const std::string name =
            ::testing::UnitTest::GetInstance()->current_test_info()->name();
        dir_ = fs::temp_directory_path()
             / ("iceDEM_AtomicFile_" + name + "_" + std::to_string(::getpid()));
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }

    void TearDown() override
    {
        fs::remove_all(dir_);
    }

    std::string path(const std::string& relative) const
    {
        return (dir_/relative).string();
    }

    static std::string contents(const std::string& file)
    {
        std::ifstream in(file, std::ios::binary);
        std::stringstream buffer;
        buffer << in.rdbuf();
        return buffer.str();
    }

    // Everything in the folder (recursively): only the files the test meant to write.
    std::size_t nFiles() const
    {
        std::size_t n = 0;
        for (const auto& entry : fs::recursive_directory_iterator(dir_))
        {
            n += entry.is_regular_file();
        }
        return n;
    }

    fs::path dir_;
};

} // namespace


TEST_F(AtomicFile, WritesContentAndLeavesNoTemporaryFile)
{
    const std::string content = "line 1\nline 2\n\0binary"s;
    writeFileAtomically(path("a.txt"), content);
    EXPECT_EQ(contents(path("a.txt")), content);
    EXPECT_EQ(nFiles(), 1u);
}


TEST_F(AtomicFile, CreatesParentFolders)
{
    writeFileAtomically(path("deep/er/b.txt"), "x");
    EXPECT_EQ(contents(path("deep/er/b.txt")), "x");
}


TEST_F(AtomicFile, ReplacesExistingFile)
{
    writeFileAtomically(path("c.txt"), "old content that is longer");
    writeFileAtomically(path("c.txt"), "new");
    EXPECT_EQ(contents(path("c.txt")), "new");
    EXPECT_EQ(nFiles(), 1u);
}


TEST_F(AtomicFile, FailingProducerKeepsOldFileAndRemovesTemporary)
{
    writeFileAtomically(path("d.txt"), "complete");
    EXPECT_THROW
    (
        writeStreamAtomically
        (
            path("d.txt"),
            [](std::ostream& out)
            {
                out << "half written";
                throw std::logic_error("producer failed");
            }
        ),
        std::logic_error
    );
    EXPECT_EQ(contents(path("d.txt")), "complete");
    EXPECT_EQ(nFiles(), 1u);
}


TEST_F(AtomicFile, CallbackWritesByName)
{
    std::string seenTemp;
    writeAtomically
    (
        path("e.dat"),
        [&](const std::string& tempPath)
        {
            seenTemp = tempPath;
            std::ofstream(tempPath) << "by name";
        }
    );
    EXPECT_EQ(fs::path(seenTemp).parent_path(), dir_);
    EXPECT_NE(fs::path(seenTemp).filename(), "e.dat");
    EXPECT_FALSE(fs::exists(seenTemp));
    EXPECT_EQ(contents(path("e.dat")), "by name");
}


TEST_F(AtomicFile, CallbackThatWritesNothingIsAnError)
{
    EXPECT_THROW(writeAtomically(path("f.dat"), [](const std::string&) {}),
                 std::runtime_error);
    EXPECT_FALSE(fs::exists(path("f.dat")));
}


TEST_F(AtomicFile, FailureNamesThePath)
{
    writeFileAtomically(path("plain"), "a file, not a folder");
    const std::string target = path("plain/g.txt");
    try
    {
        writeFileAtomically(target, "x");
        FAIL() << "expected std::runtime_error";
    }
    catch (const std::runtime_error& e)
    {
        EXPECT_NE(std::string(e.what()).find(target), std::string::npos) << e.what();
    }
}


TEST_F(AtomicFile, RelativePathInCurrentFolder)
{
    const fs::path previous = fs::current_path();
    fs::current_path(dir_);
    try
    {
        writeFileAtomically("h.txt", "here");
    }
    catch (...)
    {
        fs::current_path(previous);
        throw;
    }
    fs::current_path(previous);
    EXPECT_EQ(contents(path("h.txt")), "here");
}
