# The lowest eigenvectors of the preconditioned matrix (eig.py): localisation, translational share,
# and the iterations with exact deflation of the k lowest.
from probe import *
U = np.load(OUT + "/U40.npy"); ev = np.load(OUT + "/ev.npy")
for k in range(12):
    u = U[:, k].reshape(N, 6); w = (u ** 2).sum(1); w /= w.sum()
    top = np.argsort(-w)[:8]; tr = (u[:, :3] ** 2).sum() / (u ** 2).sum()
    print(f"ev {ev[k]:.4f} participation {1 / (w ** 2).sum():.1f} bodies, translation share {tr:.2f}, "
          f"top bodies {top} weights {np.round(w[top], 3)}")
for k in [2, 5, 12, 26, 40]:
    Z = U[:, :k]; print("exact eigvecs", k, end=" "); run("adef2", adef2(Z), Z)
