"""What the source paper (../shared/seed, SPEC §2) states, for setting our results beside it.
Only what the paper gives as numbers or words is here; the figures' curves are not digitised."""
import os

# §3.1: F = 338240·δ^1.0114 (δ in mm, F in N), t_B = 4 mm, axis-line loading, Coulomb μ = 0.1.
TB4_K_MM = 338240.0     # [N/mm^n]
TB4_N = 1.0114          # [1]
TB4_T_B = 0.004         # [m]
DELTA_MAX = 5e-5        # [m] the paper's pseudo-penetration range, 0 … 0.05 mm
YIELD_STRESS = 168.2e6  # [Pa] SPEC §2, first point of the hardening table
# §3.1: "the exponent n is reduced from 1.0254 to 1.0205" from t_B = 6 to 8 mm.
N_BY_T_B = {0.006: 1.0254, 0.008: 1.0205}


def tb4_force(delta_m):
    """[N] the paper's t_B = 4 mm law at δ [m]."""
    return TB4_K_MM * (delta_m * 1e3) ** TB4_N


def tb4_K_si():
    return TB4_K_MM * 1000.0 ** TB4_N  # [N/m^n]


def paper_law_file():
    """laws/paper_tB4.json in the source tree (the same law in SI, with its description)."""
    here = os.path.dirname(os.path.abspath(__file__))
    path = os.path.normpath(os.path.join(here, "..", "..", "laws", "paper_tB4.json"))
    return path if os.path.exists(path) else None


# The paper's claims per study: (parameter, expected sign of dF_ref/dparameter, its words).
CLAIMS = {
    "t_B": (+1, "§3.1: “the force required to produce the same pseudo-penetration is larger in "
                "thicker bearings” (Fig. 4b; its conclusion says the opposite, SPEC §2 takes the "
                "text and Fig. 4b as physical)"),
    "theta": (-1, "§3.3: “the increase of θ is followed by both the decrease in the contact force "
                  "and contact stiffness” (Fig. 8)"),
}

# What the paper modelled (§2.2, §3): for the "differs from the paper" paragraphs.
MODEL = {
    "loading": "axis_line",   # the nodes on the journal axis displaced (§3.1, §3.3)
    "mu": 0.1,                # Coulomb friction between journal and bearing
    "symmetry": "full model", # no symmetry planes mentioned
    "software": "Abaqus",
    "mesh_error": "3.12 %",   # its quoted mesh error
}
