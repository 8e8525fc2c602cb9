#include "PlatenFlexureTest.H"

#include "LiggghtsInstance.H"
#include "RidgeScene.H"
#include "SceneContext.H"
#include "StlWriter.H"

#include "fix.h"

#include <cmath>

namespace iceDEM
{

namespace
{
constexpr double platenOverhang = 0.05;     // m the platen reaches past each side wall
}


PlatenFlexureTest::PlatenFlexureTest(const RidgeSettings& settings)
:
    settings_(settings)
{}


void PlatenFlexureTest::defineFixes(LiggghtsInstance& lmp, const SceneContext& context, double topUnderPlaten)
{
    platenBottom_ = topUnderPlaten + settings_.loading.initialGap;
    const double xLoad = 0.5 * settings_.layer.length;
    if (context.master())
    {
        writeBoxStl
        (
            context.path("DEM/platen.stl"),
            Vec3(xLoad - 0.5 * settings_.platenLength, -platenOverhang, platenBottom_),
            Vec3(xLoad + 0.5 * settings_.platenLength, settings_.layer.width + platenOverhang,
                 platenBottom_ + settings_.platenHeight),
            "platen"
        );
    }
    MPI_Barrier(context.comm());
    lmp.command("fix platen all mesh/surface/stress file " + context.path("DEM/platen.stl") + " type 1");
    lmp.command("fix platenWall all wall/gran model hooke/stiffness tangential history rolling_friction epsd2 "
                "mesh n_meshes 1 meshes platen absolute_damping on");
}


double PlatenFlexureTest::force(const LiggghtsInstance& lmp, MPI_Comm, long) const
{
    // Force of the ice on the platen, which they push up.
    return lmp.fix("platen").compute_vector(2);
}


double PlatenFlexureTest::loadingBodyBuoyancy(const HydrostaticWater& water, double travel) const
{
    const double bottom = platenBottom_ - travel;
    return water.buoyancy(water.submergedPrismVolume(
        settings_.platenLength * (settings_.layer.width + 2.0 * platenOverhang), bottom, bottom + settings_.platenHeight));
}


void PlatenFlexureTest::startMotion(LiggghtsInstance& lmp, const std::string& speed, const std::string&) const
{
    lmp.command("variable platenVz equal -" + speed);
    lmp.command("fix movePlaten all move/mesh mesh platen linear/variable v_zero v_zero v_platenVz");
}


void PlatenFlexureTest::addFigures(Json& j, const RidgeGeometry& g, const CsvWriter&, double peak, double) const
{
    const double L = g.length, B = g.width, D = g.depth();
    j["flexural_strength_Pa"] = 3.0 * peak * L / (2.0 * B * D * D);
    const double sigmaF1 = settings_.referenceFlexuralStrength;
    if (sigmaF1 > 0.0)
    {
        j["equivalent_thickness_m"] = std::sqrt(3.0 * peak * L / (2.0 * sigmaF1 * B));
        j["sigma_f1_Pa"] = sigmaF1;
    }
}

} // namespace iceDEM
