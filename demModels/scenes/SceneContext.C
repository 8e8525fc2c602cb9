#include "SceneContext.H"

#include "InputError.H"
#include "LiggghtsInstance.H"

#include <filesystem>
#include <iostream>
#include <utility>

namespace iceDEM
{

SceneContext::SceneContext(MPI_Comm comm, std::string caseDir, std::string application)
:
    comm_(comm),
    caseDir_(std::move(caseDir)),
    application_(std::move(application)),
    start_(std::chrono::steady_clock::now())
{
    MPI_Comm_rank(comm_, &rank_);
    MPI_Comm_size(comm_, &ranks_);
}


std::string SceneContext::path(const std::string& relative) const
{
    return caseDir_ + "/" + relative;
}


void SceneContext::log(const std::string& line) const
{
    if (rank_ == 0)
    {
        std::cout << line << std::endl;
    }
}


double SceneContext::wallSeconds() const
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}


std::unique_ptr<LiggghtsInstance> SceneContext::startLiggghts
(
    const ScriptVariables& variables,
    const std::string& script
) const
{
    LiggghtsInstance::reportErrorsFromLog(path("log.liggghts"));
    auto lmp = std::make_unique<LiggghtsInstance>(comm_, path("log.liggghts"));
    defineScriptVariables(*lmp, variables, path("DEM/variables.generated"), application_);
    const std::string scriptPath = path(script);
    if (!std::filesystem::exists(scriptPath))
    {
        throw InputError(scriptPath, "(file)", "the LIGGGHTS input script is missing");
    }
    lmp->runScript(scriptPath);
    return lmp;
}

} // namespace iceDEM
