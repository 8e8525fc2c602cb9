#include "LiggghtsInstance.H"

#include "lammps.h"
#include "input.h"
#include "modify.h"
#include "fix.h"
#include "update.h"

#include <algorithm>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <vector>

namespace iceDEM
{

namespace
{

std::string watchedLog;
bool finishedNormally = false;

//- LIGGGHTS registers its granular model styles in a process-wide table
//  whenever a granular pair style is made, and writes one "Style collision"
//  warning to std::cerr for every entry already there: some 240 lines each
//  time a scene starts a second LIGGGHTS in one process (ridge: assembly,
//  then loading). They are harmless and drown real warnings, so this buffer
//  drops exactly those lines and passes everything else through.
class DuplicateStyleWarningFilter : public std::streambuf
{
public:
    explicit DuplicateStyleWarningFilter(std::streambuf* target) : target_(target) {}

    //- Puts the filter in front of std::cerr once per process. Never removed:
    //  LIGGGHTS instances overlap (the next made before the last is gone).
    static void install()
    {
        static DuplicateStyleWarningFilter* filter = nullptr;
        if (!filter)
        {
            filter = new DuplicateStyleWarningFilter(std::cerr.rdbuf());
            std::cerr.rdbuf(filter);
        }
    }

protected:
    int overflow(int c) override
    {
        if (c == traits_type::eof())
        {
            return traits_type::not_eof(c);
        }
        line_.push_back(static_cast<char>(c));
        if (c == '\n')
        {
            flushLine();
        }
        return c;
    }

    int sync() override
    {
        // A partial line waits for its end only while it may still become one
        // of the dropped warnings (a message without a newline is not held).
        if (!mayBeDuplicateStyleWarning(line_))
        {
            forward();
        }
        return target_->pubsync();
    }

private:
    static bool mayBeDuplicateStyleWarning(const std::string& text)
    {
        for (const std::string warning : {"WARNING! Style collision detected!",
                                          "WARNING! VariantSelector collision detected!"})
        {
            const std::size_t n = std::min(text.size(), warning.size());
            if (text.compare(0, n, warning, 0, n) == 0)
            {
                return true;
            }
        }
        return false;
    }

    void flushLine()
    {
        if (!mayBeDuplicateStyleWarning(line_))
        {
            forward();
        }
        line_.clear();
    }

    void forward()
    {
        target_->sputn(line_.data(), static_cast<std::streamsize>(line_.size()));
        line_.clear();
    }

    std::streambuf* target_;
    std::string line_;
};

} // namespace


LiggghtsInstance::LiggghtsInstance(MPI_Comm comm, const std::string& logFile)
:
    comm_(comm),
    lmp_(nullptr)
{
    DuplicateStyleWarningFilter::install();
    std::vector<std::string> args{"liggghts", "-screen", "/dev/null", "-log", logFile, "-echo", "none"};
    std::vector<char*> argv;
    for (std::string& a : args)
    {
        argv.push_back(a.data());
    }
    lmp_ = new LAMMPS_NS::LAMMPS(static_cast<int>(argv.size()), argv.data(), comm);
}


LiggghtsInstance::~LiggghtsInstance()
{
    delete lmp_;
    finishedNormally = true;
}


void LiggghtsInstance::command(const std::string& line)
{
    lmp_->input->one(line.c_str());
}


void LiggghtsInstance::runScript(const std::string& path)
{
    lmp_->input->file(path.c_str());
}


namespace
{

void printLogTail()
{
    if (finishedNormally || watchedLog.empty())
    {
        return;
    }
    std::ifstream log(watchedLog);
    std::deque<std::string> tail;
    for (std::string line; std::getline(log, line);)
    {
        tail.push_back(line);
        if (tail.size() > 8) tail.pop_front();
    }
    std::cerr << "\n--> stopped inside LIGGGHTS; the end of " << watchedLog << ":\n";
    for (const std::string& line : tail)
    {
        std::cerr << "    " << line << "\n";
    }
    std::cerr << std::endl;
}

} // namespace


void LiggghtsInstance::reportErrorsFromLog(const std::string& logFile)
{
    if (watchedLog.empty())
    {
        std::atexit(printLogTail);
    }
    watchedLog = logFile;
}


void LiggghtsInstance::setVariable(const std::string& name, const std::string& value)
{
    command("variable " + name + " delete");
    command("variable " + name + " index " + value);
}


LAMMPS_NS::Fix& LiggghtsInstance::fix(const std::string& id) const
{
    const int index = lmp_->modify->find_fix(id.c_str());
    if (index < 0)
    {
        throw std::runtime_error("LIGGGHTS has no fix with id '" + id + "'");
    }
    return *lmp_->modify->fix[index];
}


double LiggghtsInstance::time() const
{
    return lmp_->update->atime + (lmp_->update->ntimestep - lmp_->update->atimestep) * lmp_->update->dt;
}


long LiggghtsInstance::step() const
{
    return static_cast<long>(lmp_->update->ntimestep);
}


double LiggghtsInstance::timeStep() const
{
    return lmp_->update->dt;
}

} // namespace iceDEM
