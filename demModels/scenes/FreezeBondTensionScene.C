#include "FreezeBondTensionScene.H"
#include "CommandLine.H"

#include "AppMain.H"
#include "AtomicFile.H"
#include "ConfinementLineStrength.H"
#include "Dictionary.H"
#include "InputError.H"
#include "Json.H"
#include "LiggghtsInstance.H"


#include <algorithm>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>

namespace iceDEM
{

namespace
{

constexpr int bodyType = 1;
constexpr int lowerGripType = 2;
constexpr int upperGripType = 3;


} // namespace


TensionTestSettings TensionTestSettings::read(int argc, char** argv)
{
    TensionTestSettings s;
    double pressure = -1.0, time = -1.0;
    CommandLine("freezeBondTensionDEM")
        .text("-case", "DIR", "the case directory (default .)", s.caseDir)
        .text("-label", "NAME", "results go to postProcessing/runs/NAME", s.label)
        .positive("-pressure", "PA", "confinement pressure instead of loading.confinementPressure", pressure)
        .positive("-time", "MIN", "submersion time instead of constant/freezeBondProperties'", time)
        .positive("-tensileStrength", "PA", "the fixed set's tensile strength (strengthModel fixedSet)",
                  s.tensileStrength)
        .positive("-shearStrength", "PA", "the fixed set's shear strength (strengthModel fixedSet)", s.shearStrength)
        .parse(argc, argv);
    const Dictionary d = Dictionary::readFile(s.caseDir + "/constant/tensionTestProperties");
    d.checkKeys({"specimen", "loading"});
    s.specimen = SpecimenGeometry::read(d.subDict("specimen"), s.specimen);
    const Dictionary& l = d.subDict("loading");
    l.checkKeys({"confinementPressure", "confinementTime", "pullSpeed", "maxPull", "samples"});
    s.confinementPressure = l.getPositiveScalarOrDefault("confinementPressure", s.confinementPressure);
    s.confinementTime = l.getPositiveScalarOrDefault("confinementTime", s.confinementTime);
    s.pullSpeed = l.getPositiveScalarOrDefault("pullSpeed", s.pullSpeed);
    s.maxPull = l.getPositiveScalarOrDefault("maxPull", s.maxPull);
    s.samples = l.getLabelOrDefault("samples", s.samples);
    if (s.samples < 10) l.fail("samples", "must be at least 10");
    if (pressure > 0.0) s.confinementPressure = pressure;
    s.submersionTime = time;
    if (s.label.empty())
    {
        std::ostringstream label;
        label << "p" << s.confinementPressure*1e-3 << "kPa";
        if (time > 0.0) label << "_t" << time << "min";
        s.label = label.str();
    }
    return s;
}


FreezeBondTensionScene::FreezeBondTensionScene(MPI_Comm comm, const TensionTestSettings& settings)
:
    settings_(settings),
    specimen_(comm, settings.caseDir, "freezeBondTensionDEM", settings.submersionTime),
    area_(M_PI*0.25*settings.specimen.diameter*settings.specimen.diameter),
    curve_({"time_s", "pull_m", "force_N", "stress_Pa", "intact_freeze_bonds"})
{
    settings_.submersionTime = specimen_.freezeBondProperties().submersionTime();
    if (settings_.tensileStrength > 0.0 || settings_.shearStrength > 0.0)
    {
        // The set's own strength where only one is overridden (fixedSet: the same at any confinement).
        const FreezeBondStrengthModel& set = specimen_.freezeBondProperties().strengthModel();
        const double tensile = settings_.tensileStrength > 0.0 ? settings_.tensileStrength : set.tensile(0.0);
        const double shear = settings_.shearStrength > 0.0 ? settings_.shearStrength : set.shear(set.tensile(0.0));
        specimen_.freezeBondProperties().setSetStrengths(tensile, shear);
    }
}


void FreezeBondTensionScene::confine()
{
    const double load = settings_.confinementPressure*area_;
    std::ostringstream fix;
    fix << std::setprecision(17) << "fix confine upperGrip addforce 0 0 "
        << -load/specimen_.atomsOfType(upperGripType);
    specimen_.liggghts().command(fix.str());
    specimen_.fixesChanged();
    const long steps = static_cast<long>(std::ceil(settings_.confinementTime/specimen_.dt()));
    specimen_.run(steps);
    confinementReaction_ = -specimen_.forceOnType(lowerGripType, 2);
    std::ostringstream msg;
    msg << "Confined at " << settings_.confinementPressure*1e-3 << " kPa for " << settings_.confinementTime
        << " s: lower-grip reaction " << confinementReaction_ << " N of " << load << " N applied";
    specimen_.context().log(msg.str());
    if (std::abs(confinementReaction_/load - 1.0) > 0.02)
    {
        throw RunError("the specimen did not come to rest under the confinement (reaction "
            + std::to_string(confinementReaction_) + " N against " + std::to_string(load)
            + " N): raise loading.confinementTime in constant/tensionTestProperties");
    }
}


void FreezeBondTensionScene::pull()
{
    LiggghtsInstance& lmp = specimen_.liggghts();
    lmp.command("unfix confine");
    specimen_.fixesChanged();
    // Let the unloaded specimen relax before pulling.
    specimen_.run(static_cast<long>(std::ceil(0.2*settings_.confinementTime/specimen_.dt())));
    lmp.command("unfix integrateUpperGrip");
    lmp.command("velocity upperGrip set 0 0 0");
    lmp.command("fix pull upperGrip move linear 0 0 " + exactNumber(settings_.pullSpeed));
    specimen_.fixesChanged();

    const double t0 = specimen_.time();
    const long stepsPerSample =
        std::max(1L, static_cast<long>(settings_.maxPull/settings_.pullSpeed/specimen_.dt()/settings_.samples));
    bool failed = false;
    for (int s = 0; s <= settings_.samples && !failed; ++s)
    {
        specimen_.run(stepsPerSample);
        const double force = specimen_.forceOnType(lowerGripType, 2);
        const long intact = specimen_.intactFreezeBonds();
        specimen_.collectBreaks();
        specimen_.checkHealth();
        const double pull = settings_.pullSpeed*(specimen_.time() - t0);
        curve_.addRow({specimen_.time(), pull, force, force/area_, double(intact)});
        if (force > peakForce_)
        {
            peakForce_ = force;
            pullAtPeak_ = pull;
        }
        failed = intact == 0 && force < 0.05*peakForce_;
    }
    std::ostringstream msg;
    msg << "Pulled " << curve_.row(curve_.nRows() - 1)[1]*1e3 << " mm: peak " << peakForce_ << " N, strength "
        << peakForce_/area_*1e-3 << " kPa" << (failed ? "" : " (NOT fully separated: raise loading.maxPull)");
    specimen_.context().log(msg.str());
}


void FreezeBondTensionScene::writeSummary(double wallSeconds) const
{
    if (specimen_.context().rank() != 0)
    {
        return;
    }
    const std::string dir = specimen_.writeRunRecord(settings_.label);
    curve_.write(dir + "/forceDisplacement.csv");
    std::vector<double> strengths;
    for (const NewFreezeBond& b : specimen_.freezeBonds())
    {
        strengths.push_back(b.strength.tensile);
    }
    const FreezeBondingStatistics& stats = specimen_.freezeStatistics();
    const FreezeBondProperties& model = specimen_.freezeBondProperties();
    // fixedSet has no line: 0 for both.
    const auto* line = dynamic_cast<const ConfinementLineStrength*>(&model.strengthModel());
    Json j;
    j["case"] = "freezeBondTension";
    j["label"] = settings_.label;
    j["confinement_pressure_Pa"] = settings_.confinementPressure;
    j["submersion_time_min"] = settings_.submersionTime;
    j["model_slope"] = line ? line->slope() : 0.0;
    j["model_intercept_Pa"] = line ? line->intercept() : 0.0;
    j["area_correction"] = model.areaCorrection().value();
    j["peak_force_N"] = peakForce_;
    j["strength_Pa"] = peakForce_/area_;
    j["pull_at_peak_m"] = pullAtPeak_;
    j["specimen_area_m2"] = area_;
    j["freeze_bonds"] = long(stats.bonds);
    j["mean_measured_confinement_Pa"] = stats.meanConfinement;
    j["max_measured_confinement_Pa"] = stats.maxConfinement;
    j["confinement_reaction_N"] = confinementReaction_;
    j["bond_tensile_strength_mean_Pa"] = stats.meanTensile;
    j["bond_tensile_strength_sd_Pa"] = stats.sdTensile;
    j["bond_shear_strength_mean_Pa"] = stats.meanShear;
    j["freeze_bond_area_m2"] = specimen_.freezeBondArea();
    j["bond_tensile_strengths_Pa"] = strengths;
    specimen_.addRunFigures(j, wallSeconds);
    writeFileAtomically(dir + "/summary.json", jsonText(j));
}


void FreezeBondTensionScene::run()
{
    const auto start = std::chrono::steady_clock::now();
    specimen_.build(settings_.specimen, 3, [&](int layer, const ParticleSpec&)
    {
        const int lastLayer = 2*specimen_.layersPerHalf() - 1;
        return layer == 0 ? lowerGripType : layer == lastLayer ? upperGripType : bodyType;
    });
    specimen_.start("in.freezeBondTension", {}, settings_.maxPull + 0.05);
    confine();
    specimen_.freezeBond(area_);
    pull();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeSummary(wall);
    specimen_.context().log("Wall time " + formatDuration(wall) + "; results in postProcessing/runs/" + settings_.label);
}

} // namespace iceDEM
