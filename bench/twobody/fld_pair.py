"""An independent Python statement of the FLD pair model of sdk/lubrication (LubricationPair.cpp,
BodyResistance.cpp) for two equal isolated spheres, in every convention: the isolated-sphere drag
(6 pi mu a, 8 pi mu a^3; `lubrication` plugin, or `fld` at phi -> 0) plus the lubrication modes
  squeeze  c_sq = 6 pi mu a (1/(4 xi) + 9/40 ln(1/xi))     on d.(u2 - u1)
  shear    c_sh = 6 pi mu a (1/6) ln(1/xi)                 on P(u2 - u1 - (l w1 + l w2) x d)
  pump     c_pu = 8 pi mu a^3 (3/40 or 3/160) ln(1/xi)     on P(w1 - w2)
  twist    c_tw = 8 pi mu a^3 (zeta(3) - 1)/2              on d.(w1 - w2)
with the lever l = r/2 (centre) or a (contact), and the strain forcing that treats the ambient
relative velocity across the pair as arm E.d with arm = r (centre) or 2a (contact). The taper
(smooth) multiplies all four coefficients by T(r) = 1 - t^3 (10 - 15 t + 6 t^2),
t = (r - cutoff + w)/w on [cutoff - w, cutoff] (w = 0.3 a); none leaves them as they are.
The C++ program bench/twobody (fldsim_twobody) evaluates the same quantities through the real
plugin code; this file is the cross-check and the place to try a convention before it exists.
Units as free_pair.py (a = 1, 6 pi mu a = 1)."""
import math

import numpy as np

from free_pair import SA, SC

ZETA3 = 1.2020569031595942


def coefficients(s, conv):
    xi = max(s - 2.0, conv.get("delta_num", 1e-5))
    L = math.log(1.0 / xi) if xi < 1.0 else 0.0
    c = {
        "squeeze": SA * (1.0 / (4.0 * xi) + 9.0 / 40.0 * L),
        "shear": SA * L / 6.0,
        "pump": SC * (3.0 / 160.0 if conv["pump"] == "lammps" else 3.0 / 40.0) * L,
        "twist": SC * 0.5 * (ZETA3 - 1.0) if conv["twist"] else 0.0,
    }
    T = taper(s, conv)
    return {k: T * v for k, v in c.items()}


def taper(s, conv, cutoff=2.5):
    w = conv.get("taper_width", 0.3) if conv.get("taper", "none") == "smooth" else 0.0
    if w <= 0.0:
        return 1.0
    t = (s - cutoff + w) / w
    return 1.0 if t <= 0.0 else 0.0 if t >= 1.0 else 1.0 - t ** 3 * (10.0 - 15.0 * t + 6.0 * t * t)


def rows(s, d, conv):
    """8 x 12 mode matrix S (rows sqrt(c_m) G_m) acting on (u1, w1, u2, w2)."""
    c = coefficients(s, conv)
    lever = s / 2.0 if conv["lever"] == "centre" else 1.0
    P = np.eye(3) - np.outer(d, d)
    D = np.array([[0, -d[2], d[1]], [d[2], 0, -d[0]], [-d[1], d[0], 0]])  # D w = d x w
    S = np.zeros((8, 12))
    S[0, 0:3], S[0, 6:9] = -math.sqrt(c["squeeze"]) * d, math.sqrt(c["squeeze"]) * d
    sh = math.sqrt(c["shear"])
    S[1:4, 0:3], S[1:4, 3:6] = -sh * P, sh * lever * D
    S[1:4, 6:9], S[1:4, 9:12] = sh * P, sh * lever * D
    pu = math.sqrt(c["pump"])
    S[4:7, 3:6], S[4:7, 9:12] = pu * P, -pu * P
    tw = math.sqrt(c["twist"])
    S[7, 3:6], S[7, 9:12] = tw * d, -tw * d
    return S


def model(conv, cutoff=2.5):
    """description(s, d) -> (R, RE) of the FLD pair under convention conv (a dict)."""

    def description(s, d):
        R = np.diag([SA] * 3 + [SC] * 3 + [SA] * 3 + [SC] * 3).astype(float)
        if s >= cutoff:
            return R, lambda E: np.zeros(12)
        S = rows(s, d, conv)
        R += S.T @ S
        arm = s if conv["strain_arm"] == "centre" else 2.0

        def RE(E):
            return -S.T @ (S[:, 6:9] @ (arm * (E @ d)))

        return R, RE

    return description


CONVENTIONS = [
    {"strain_arm": sa, "lever": lv, "pump": pu, "twist": tw, "taper": tp}
    for sa in ("centre", "contact") for lv in ("centre", "contact")
    for pu in ("jeffrey_onishi", "lammps") for tw in (True, False) for tp in ("none", "smooth")
]


def label(conv):
    return (f"arm={conv['strain_arm']},lever={conv['lever']},pump={conv['pump']},"
            f"twist={'on' if conv['twist'] else 'off'},taper={conv['taper']}")


if __name__ == "__main__":
    # Same CSV as fldsim_twobody, from this statement of the model (taper none): python3 fld_pair.py s1 s2 ...
    import sys

    import free_pair

    print("plugin,convention,s,G,H,A,B,C,Xr,Yr")
    for conv in CONVENTIONS:
        label_ = (f"strain_arm={conv['strain_arm']};lever={conv['lever']};pump={conv['pump']};"
                  f"twist={'true' if conv['twist'] else 'false'};taper={conv['taper']}")
        for s in map(float, sys.argv[1:]):
            f = free_pair.free_pair_functions(model(conv), s)
            print(f"python,{label_},{s:.6f}," + ",".join(f"{f[q]:.10g}" for q in ("G", "H", "A", "B", "C", "Xr", "Yr")))
