#include "FreezeBondShearScene.H"
#include "CommandLine.H"

#include "AppMain.H"
#include "AtomicFile.H"
#include "Dictionary.H"
#include "ForceCurveAnalysis.H"
#include "InputError.H"
#include "Json.H"
#include "LiggghtsInstance.H"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <iomanip>
#include <sstream>

namespace iceDEM
{

namespace
{

constexpr int bodyType = 1;
constexpr int rollerType = 2;      // supports below: held in x and y, free along the axis
constexpr int outerLoadType = 3;   // load above, outer layer left of the plane
constexpr int innerLoadType = 4;   // load above, inner layer right of the plane
constexpr int lowerPlateType = 5;  // end plates: the confinement
constexpr int upperPlateType = 6;


} // namespace


ShearTestSettings ShearTestSettings::read(int argc, char** argv)
{
    ShearTestSettings s;
    s.specimen.halfLength = 0.1;
    double pressure = -1.0;
    CommandLine("freezeBondShearDEM")
        .text("-case", "DIR", "the case directory (default .)", s.caseDir)
        .text("-label", "NAME", "results go to postProcessing/runs/NAME", s.label)
        .positive("-shearStrength", "PA", "particle-level freeze-bond shear strength", s.shearStrength)
        .positive("-tensileStrength", "PA", "particle-level freeze-bond tensile strength (default: -shearStrength's)",
                  s.tensileStrength)
        .positive("-youngsModulus", "PA", "freeze-bond Young's modulus", s.youngsModulus)
        .positive("-pressure", "PA", "confinement pressure instead of loading.confinementPressure", pressure)
        .parse(argc, argv);
    const Dictionary d = Dictionary::readFile(s.caseDir + "/constant/shearTestProperties");
    d.checkKeys({"specimen", "loading"});
    s.specimen = SpecimenGeometry::read(d.subDict("specimen"), s.specimen);
    const Dictionary& l = d.subDict("loading");
    l.checkKeys({"confinementPressure", "confinementTime", "innerLayer", "outerLayer", "loadRate", "maxLoad",
                 "samples"});
    s.confinementPressure = l.getPositiveScalarOrDefault("confinementPressure", s.confinementPressure);
    s.confinementTime = l.getPositiveScalarOrDefault("confinementTime", s.confinementTime);
    s.innerLayer = l.getLabelOrDefault("innerLayer", s.innerLayer);
    s.outerLayer = l.getLabelOrDefault("outerLayer", s.outerLayer);
    if (s.innerLayer < 0) l.fail("innerLayer", "must be 0 or more");
    if (s.outerLayer <= s.innerLayer) l.fail("outerLayer", "must lie beyond innerLayer");
    s.loadRate = l.getPositiveScalarOrDefault("loadRate", s.loadRate);
    s.maxLoad = l.getPositiveScalarOrDefault("maxLoad", s.maxLoad);
    s.samples = l.getLabelOrDefault("samples", s.samples);
    if (s.samples < 10) l.fail("samples", "must be at least 10");
    if (pressure > 0.0) s.confinementPressure = pressure;
    if (s.label.empty())
    {
        std::ostringstream label;
        label << "S" << (s.shearStrength > 0 ? s.shearStrength*1e-3 : 0) << "kPa_E" << (s.youngsModulus > 0 ? s.youngsModulus : 0);
        s.label = label.str();
    }
    return s;
}


FreezeBondShearScene::FreezeBondShearScene(MPI_Comm comm, const ShearTestSettings& settings)
:
    settings_(settings),
    specimen_(comm, settings.caseDir, "freezeBondShearDEM", -1.0),
    area_(M_PI*0.25*settings.specimen.diameter*settings.specimen.diameter),
    curve_({"time_s", "load_N", "shear_force_N", "tau_max_Pa", "slip_m", "intact_freeze_bonds"})
{
    if (settings_.shearStrength > 0.0 || settings_.tensileStrength > 0.0)
    {
        // The set's own strengths where only one is overridden (fixedSet: the same at any confinement).
        const FreezeBondStrengthModel& set = specimen_.freezeBondProperties().strengthModel();
        const double shear = settings_.shearStrength > 0.0 ? settings_.shearStrength : set.shear(set.tensile(0.0));
        const double tensile = settings_.tensileStrength > 0.0 ? settings_.tensileStrength
            : settings_.shearStrength > 0.0 ? settings_.shearStrength : set.tensile(0.0);
        specimen_.freezeBondProperties().setSetStrengths(tensile, shear);
    }
    if (settings_.youngsModulus > 0.0)
    {
        specimen_.setFreezeModulus(settings_.youngsModulus);
    }
}


void FreezeBondShearScene::confine()
{
    LiggghtsInstance& lmp = specimen_.liggghts();
    const double load = settings_.confinementPressure*area_;
    std::ostringstream fix;
    fix << std::setprecision(17)
        << "fix lowerPlate lowerPlate addforce 0 0 " << load/specimen_.atomsOfType(lowerPlateType);
    lmp.command(fix.str());
    fix.str("");
    fix << "fix upperPlate upperPlate addforce 0 0 " << -load/specimen_.atomsOfType(upperPlateType);
    lmp.command(fix.str());
    // Rollers: after the bond fix, so that nothing moves them sideways.
    lmp.command("fix rollers rollers setforce 0.0 0.0 NULL");
    specimen_.fixesChanged();
    specimen_.run(static_cast<long>(std::ceil(settings_.confinementTime/specimen_.dt())));
}


void FreezeBondShearScene::load()
{
    const int n = specimen_.layersPerHalf();
    const double si = std::abs(specimen_.layerHeight(n + settings_.innerLayer));
    const double so = std::abs(specimen_.layerHeight(n + settings_.outerLayer));
    a_ = si/so;
    // A pivoted loading beam splits P so that the plane carries no moment.
    const double shareOuter = si/(si + so), shareInner = so/(si + so);
    LiggghtsInstance& lmp = specimen_.liggghts();
    const long step0 = lmp.step();
    auto rampFix = [&](const std::string& id, int type, double share)
    {
        std::ostringstream v;
        v << std::setprecision(17) << "variable " << id << "Force equal -" << settings_.loadRate*share
          /specimen_.atomsOfType(type) << "*(step-" << step0 << ")*" << specimen_.dt();
        lmp.command(v.str());
        lmp.command("fix " + id + " " + id + " addforce v_" + id + "Force 0.0 0.0");
    };
    // The load fixes come after the rollers': move the rollers' fix last again.
    lmp.command("unfix rollers");
    rampFix("outerLoad", outerLoadType, shareOuter);
    rampFix("innerLoad", innerLoadType, shareInner);
    lmp.command("fix rollers rollers setforce 0.0 0.0 NULL");
    specimen_.fixesChanged();

    const double duration = settings_.maxLoad/settings_.loadRate;
    const long stepsPerSample = std::max(1L, static_cast<long>(duration/specimen_.dt()/settings_.samples));
    const long initialBonds = specimen_.intactFreezeBonds();
    // Slip across the plane: the left half is pushed up (+x) relative to the right.
    const double slip0 = specimen_.meanPositionOfLayer(n - 1, 0) - specimen_.meanPositionOfLayer(n, 0);
    const double shearFactor = (1.0 - a_)/(1.0 + a_);
    int afterFailure = 0;
    for (int s = 0; s <= settings_.samples && afterFailure < 5; ++s)
    {
        specimen_.run(stepsPerSample);
        const double P = settings_.loadRate*(lmp.step() - step0)*specimen_.dt();
        const double slip = specimen_.meanPositionOfLayer(n - 1, 0) - specimen_.meanPositionOfLayer(n, 0) - slip0;
        const long intact = specimen_.intactFreezeBonds();
        specimen_.collectBreaks();
        specimen_.checkHealth();
        const double V = shearFactor*P;
        curve_.addRow({specimen_.time(), P, V, 4.0/3.0*V/area_, slip, double(intact)});
        if (2*intact >= initialBonds)
        {
            peakLoad_ = P;
        }
        else
        {
            failed_ = true;
            ++afterFailure;
        }
    }
    // Effective shear modulus of the joint: mean shear stress over the slip
    // across the plane per layer spacing, fitted below half the peak.
    std::vector<double> gamma, tau;
    for (std::size_t k = 0; k < curve_.nRows(); ++k)
    {
        if (curve_.row(k)[1] <= 0.5*peakLoad_)
        {
            gamma.push_back(curve_.row(k)[4]/specimen_.layerSpacing());
            tau.push_back(curve_.row(k)[2]/area_);
        }
    }
    double sxx = 0, sxy = 0;
    for (std::size_t k = 0; k < gamma.size(); ++k)
    {
        sxx += gamma[k]*gamma[k];
        sxy += gamma[k]*tau[k];
    }
    effectiveShearModulus_ = sxx > 0 ? sxy/sxx : 0.0;
    std::ostringstream msg;
    msg << "Load " << peakLoad_ << " N at failure: shear " << shearFactor*peakLoad_ << " N across the plane, tau_max "
        << 4.0/3.0*shearFactor*peakLoad_/area_*1e-3 << " kPa (a = " << a_ << "); effective shear modulus "
        << effectiveShearModulus_ << " Pa" << (failed_ ? "" : " (NOT failed: raise loading.maxLoad)");
    specimen_.context().log(msg.str());
}


void FreezeBondShearScene::writeSummary(double wallSeconds) const
{
    if (specimen_.context().rank() != 0)
    {
        return;
    }
    const std::string dir = specimen_.writeRunRecord(settings_.label);
    curve_.write(dir + "/loadSlip.csv");
    const double shearFactor = (1.0 - a_)/(1.0 + a_);
    const FreezeBondingStatistics& stats = specimen_.freezeStatistics();
    long shearBreaks = 0;
    for (const BreakEvent& e : specimen_.breakage().events())
    {
        shearBreaks += e.mode == BreakMode::shear;
    }
    Json j;
    j["case"] = "freezeBondShear";
    j["label"] = settings_.label;
    j["particle_shear_strength_Pa"] = stats.meanShear;
    j["particle_tensile_strength_Pa"] = stats.meanTensile;
    j["freeze_youngs_modulus_Pa"] = specimen_.ice().family(BondFamily::freeze).youngsModulus;
    j["a"] = a_;
    j["peak_load_N"] = peakLoad_;
    j["effective_shear_strength_Pa"] = 4.0/3.0*shearFactor*peakLoad_/area_;
    j["effective_shear_modulus_Pa"] = effectiveShearModulus_;
    j["failed"] = failed_;
    j["freeze_bonds"] = long(stats.bonds);
    j["breaks_in_shear"] = shearBreaks;
    j["breaks"] = long(specimen_.breakage().size());
    j["confinement_pressure_Pa"] = settings_.confinementPressure;
    j["mean_measured_confinement_Pa"] = stats.meanConfinement;
    j["specimen_area_m2"] = area_;
    j["freeze_bond_area_m2"] = specimen_.freezeBondArea();
    specimen_.addRunFigures(j, wallSeconds);
    writeFileAtomically(dir + "/summary.json", jsonText(j));
}


void FreezeBondShearScene::run()
{
    const auto start = std::chrono::steady_clock::now();
    const double R = 0.5*settings_.specimen.diameter;
    const double d = settings_.specimen.particleDiameter;
    specimen_.build(settings_.specimen, 6, [&](int layer, const ParticleSpec& p)
    {
        const int n = specimen_.layersPerHalf();
        const bool top = p.position.x() > R - d;
        const bool bottom = p.position.x() < -R + d;
        if (layer == 0) return lowerPlateType;
        if (layer == 2*n - 1) return upperPlateType;
        if (bottom && (layer == n - 1 - settings_.innerLayer || layer == n + settings_.outerLayer)) return rollerType;
        if (top && layer == n - 1 - settings_.outerLayer) return outerLoadType;
        if (top && layer == n + settings_.innerLayer) return innerLoadType;
        return bodyType;
    });
    if (settings_.outerLayer >= specimen_.layersPerHalf() - 1)
    {
        throw InputError(specimen_.context().path("constant/shearTestProperties"), "loading.outerLayer",
            "must lie inside the specimen, below " + std::to_string(specimen_.layersPerHalf() - 1));
    }
    specimen_.start("in.freezeBondShear", {}, 0.05);
    confine();
    specimen_.freezeBond(area_);
    load();
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    writeSummary(wall);
    specimen_.context().log("Wall time " + formatDuration(wall) + "; results in postProcessing/runs/" + settings_.label);
}

} // namespace iceDEM
