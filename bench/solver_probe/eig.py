# Spectrum of the IC(0)-preconditioned matrix C^T A C (M^-1 = C C^T) and its 40 lowest eigenvectors
# in the original space (about 10 minutes at N = 1000), into PROBE_OUT.
from probe import *
C = np.linalg.cholesky((Minv + Minv.T) / 2)
ev, V = np.linalg.eigh(C.T @ A @ C)
np.save(OUT + "/U40.npy", C @ V[:, :40]); np.save(OUT + "/ev.npy", ev)
print("condition", ev[-1] / ev[0], "below 0.03/0.1/0.3:", [(ev < t).sum() for t in (0.03, 0.1, 0.3)])
