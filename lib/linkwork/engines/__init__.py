"""Numerical engines shared by the papers: kinematics (dyad chains), fem (beam elements), chains
(mechanical networks), optimize (penalty-function SUMT), multibody (planar dynamics with clearance
joints).  Engines import nothing from papers or the pipeline."""
