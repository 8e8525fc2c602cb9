// ridgeDEM: rubble punch, ridge flexure and keel-to-layer bond tests
// (scenes.md sections 6-8). Usage: ridgeDEM [-case DIR] [-stage assemble|load|all] [-resume]

#include "AppMain.H"
#include "RidgeScene.H"

int main(int argc, char** argv)
{
    return iceDEM::runApplication(argc, argv, "ridgeDEM", [&](MPI_Comm comm)
    {
        iceDEM::RidgeScene scene(comm, iceDEM::RidgeSettings::read(argc, argv));
        scene.run();
    });
}
