"""Hand a case to the finite-element solvers engineers trust: Abaqus/CalculiX decks, CalculiX runs.

:mod:`.deck` writes a complete ``.inp`` deck (mesh, sets, material, support
motion, step); :mod:`.calculix` runs ``ccx``; :mod:`.frd` reads its results;
:mod:`.solve` turns them into a ``section-result``; :mod:`.validation`
compares the project's models with it.
"""
