#include "fluidFractionSmoothing.H"
#include "fvm.H"
#include "zeroGradientFvPatchFields.H"

namespace Foam
{
namespace iceCoupling
{

fluidFractionSmoothing::fluidFractionSmoothing(const fvMesh& mesh, const dictionary& couplingProperties)
:
    mesh_(mesh),
    length_(couplingProperties.getOrDefault<scalar>("smoothingLength", 0))
{
    if (length_ < 0)
    {
        FatalIOErrorInFunction(couplingProperties)
            << "entry 'smoothingLength' is " << length_ << ": it must be >= 0 (m; 0 or absent:"
            << " no smoothing of the fluid fraction)" << exit(FatalIOError);
    }
}


void fluidFractionSmoothing::smooth(scalarField& solidFraction) const
{
    if (!active())
    {
        return;
    }
    volScalarField s
    (
        IOobject("solidFraction", mesh_.time().timeName(), mesh_, IOobject::NO_READ, IOobject::NO_WRITE),
        mesh_, dimensionedScalar("zero", dimless, 0), zeroGradientFvPatchScalarField::typeName
    );
    s.primitiveFieldRef() = solidFraction;
    s.correctBoundaryConditions();
    const volScalarField unsmoothed("solidFractionUnsmoothed", s);

    fvScalarMatrix diffusion
    (
        fvm::Sp(dimensionedScalar("one", dimless, 1), s)
      - fvm::laplacian(dimensionedScalar("L2", dimArea, sqr(length_)), s)
     ==
        unsmoothed
    );
    // Its own solver settings: the case's fvSolution need not know it.
    dictionary solver;
    solver.add("solver", "PCG");
    solver.add("preconditioner", "DIC");
    solver.add("tolerance", 1e-13);
    solver.add("relTol", 0);
    diffusion.solve(solver);
    solidFraction = s.primitiveField();
}

} // namespace iceCoupling
} // namespace Foam
