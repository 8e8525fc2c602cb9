#include "LiggghtsInstance.H"

#include "lammps.h"
#include "input.h"
#include "modify.h"
#include "fix.h"
#include "update.h"

#include <cstdlib>
#include <deque>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <vector>

namespace iceDEM
{

namespace
{

std::string watchedLog;
bool finishedNormally = false;

} // namespace


LiggghtsInstance::LiggghtsInstance(MPI_Comm comm, const std::string& logFile)
:
    comm_(comm),
    lmp_(nullptr)
{
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
