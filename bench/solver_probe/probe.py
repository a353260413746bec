"""The dumped solve (probe.patch) and what every script here needs from it.

Importing this module reads the dump (PROBE_DUMP) and the checkpoint of the state it came from
(PROBE_CHECKPOINT, for the body positions); PROBE_OUT holds the spectrum eig.py writes.
"""
import os
import h5py
import numpy as np

DUMP = os.environ.get("PROBE_DUMP", "/work/runs/defl/solve.bin")
CHECKPOINT = os.environ.get("PROBE_CHECKPOINT",
                            os.path.join(os.path.dirname(__file__), "../../results/sensitivity/"
                                         "nobrown-nopump-phi0.3-n1000.h5.checkpoint"))
OUT = os.environ.get("PROBE_OUT", "/work/runs/defl")


def load(path=DUMP):
    """n, CG tolerance, R (dense), b, the warm start, M^-1 (dense: column k = M^-1 e_k)."""
    with open(path, "rb") as f:
        n = int(np.frombuffer(f.read(8), np.int64)[0])
        tol = np.frombuffer(f.read(8))[0]
        A = np.frombuffer(f.read(8 * n * n)).reshape(n, n, order="F").copy()
        b = np.frombuffer(f.read(8 * n)).copy()
        x0 = np.frombuffer(f.read(8 * n)).copy()
        Minv = np.frombuffer(f.read(8 * n * n)).reshape(n, n).T.copy()
    return n, tol, A, b, x0, Minv


def pcg(A, b, x0, prec, tol, maxit=2000):
    """Preconditioned CG with the core's stopping rule |b - A x| <= tol |b|: (x, iterations)."""
    x = x0.copy(); r = b - A @ x; bn = np.linalg.norm(b)
    if np.linalg.norm(r) <= tol * bn:
        return x, 0
    z = prec(r); p = z.copy(); rz = r @ z
    for it in range(1, maxit + 1):
        q = A @ p; al = rz / (p @ q); x += al * p; r -= al * q
        if np.linalg.norm(r) <= tol * bn:
            return x, it
        z = prec(r); rz2 = r @ z; p = z + (rz2 / rz) * p; rz = rz2
    return x, maxit


n, tol, A, b, x0, Minv = load(); N = n // 6
Mi = lambda r: Minv @ r
Ab = A.reshape(N, 6, N, 6).transpose(0, 2, 1, 3)  # Ab[i, j] = block (i, j)
# StiffClusterFill's strength: |trace of the translational part| / the smaller diagonal trace.
_tt = np.trace(Ab[:, :, :3, :3], axis1=2, axis2=3); _dg = np.diag(_tt).copy()
ratio = np.abs(_tt) / np.minimum.outer(_dg, _dg); np.fill_diagonal(ratio, 0)
# A scale-free strength: |A_ij|_F / sqrt(|A_ii|_F |A_jj|_F).
_nrm = np.linalg.norm(Ab, axis=(2, 3)); _d = np.sqrt(np.diag(_nrm))
frobenius = _nrm / np.outer(_d, _d); np.fill_diagonal(frobenius, 0)

with h5py.File(CHECKPOINT) as _h:
    pos, L, strain = _h["positions"][()], float(_h["box_edge"][()]), float(_h["strain"][()])
_off = (strain * L) % L  # Lees-Edwards offset (x flow, y gradient)


def rel(i, j):
    """Minimum-image x_j - x_i through the Lees-Edwards boundary."""
    v = pos[j] - pos[i]; ny = np.round(v[1] / L); v[1] -= ny * L; v[0] -= ny * _off
    v[0] -= L * np.round(v[0] / L); v[2] -= L * np.round(v[2] / L)
    return v


def components(strength, theta):
    """Groups of bodies joined by blocks with strength > theta: labels, and positions unwrapped
    within each group (for its rigid-body modes)."""
    lab = -np.ones(N, int); R = np.zeros((N, 3)); c = 0
    for s in range(N):
        if lab[s] >= 0:
            continue
        lab[s] = c; stack = [s]
        while stack:
            i = stack.pop()
            for j in np.nonzero(strength[i] > theta)[0]:
                if lab[j] < 0:
                    lab[j] = c; R[j] = R[i] + rel(i, j); stack.append(j)
        c += 1
    return lab, R


def basis(lab, R, rot=True, minsize=2):
    """Coarse space: each group's translations (and rotations) as 6N-vectors."""
    cols = []
    for c in range(lab.max() + 1):
        m = np.nonzero(lab == c)[0]
        if len(m) < minsize:
            continue
        X = R[m].mean(0)
        for k in range(3):
            z = np.zeros(n); z[6 * m + k] = 1; cols.append(z)
        if rot:
            for k in range(3):
                e = np.zeros(3); e[k] = 1; z = np.zeros(n)
                for i in m:
                    z[6 * i:6 * i + 3] = np.cross(e, R[i] - X); z[6 * i + 3 + k] = 1
                cols.append(z)
    return np.array(cols).T


def adef2(Z, M=Mi):
    """A-DEF2 preconditioner (Tang, Nabben, Vuik & Erlangga 2009): M^-1 r + Z E^-1 (Z^T r - (AZ)^T M^-1 r)."""
    AZ = A @ Z; Ei = np.linalg.inv(Z.T @ AZ)
    return lambda r: (lambda s: s + Z @ (Ei @ (Z.T @ r - AZ.T @ s)))(M(r))


def run(name, prec, Z=None, rhs=b, start=x0):
    """Iterations from the warm start and from zero (with Z: the start x = Q b + P^T x0 A-DEF2 needs)."""
    cold = np.zeros(n)
    if Z is not None:
        Ei = np.linalg.inv(Z.T @ A @ Z)
        start = start + Z @ (Ei @ (Z.T @ (rhs - A @ start)))
        cold = Z @ (Ei @ (Z.T @ rhs))
    print(f"{name}: warm {pcg(A, rhs, start, prec, tol)[1]} cold {pcg(A, rhs, cold, prec, tol)[1]}", flush=True)
