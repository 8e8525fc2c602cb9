// freezeBondShearDEM: the virtual freeze-bond shear test, asymmetric
// four-point bending (scenes.md section 4).
//
// Usage: freezeBondShearDEM [-case DIR] [-label NAME] [-shearStrength PA] [-tensileStrength PA]
//                           [-youngsModulus PA] [-pressure PA]
// Reads  constant/{iceProperties,freezeBondProperties,shearTestProperties},
//        DEM/in.freezeBondShear
// Writes postProcessing/runs/<label>/{summary.json,loadSlip.csv,breakage.h5}

#include "AppMain.H"
#include "FreezeBondShearScene.H"

int main(int argc, char** argv)
{
    return iceDEM::runApplication(argc, argv, "freezeBondShearDEM", [&](MPI_Comm comm)
    {
        iceDEM::FreezeBondShearScene scene(comm, iceDEM::ShearTestSettings::read(argc, argv));
        scene.run();
    });
}
