import numpy as np, h5py
def load(path="/work/runs/defl/solve.bin"):
    f = open(path, "rb")
    n = int(np.frombuffer(f.read(8), np.int64)[0]); tol = np.frombuffer(f.read(8))[0]
    A = np.frombuffer(f.read(8*n*n)).reshape(n, n, order="F").copy()
    b = np.frombuffer(f.read(8*n)).copy(); x0 = np.frombuffer(f.read(8*n)).copy()
    Minv = np.frombuffer(f.read(8*n*n)).reshape(n, n).T.copy()  # column k = M^-1 e_k
    return n, tol, A, b, x0, Minv
def positions(path="/work/wt/lead/results/sensitivity/nobrown-nopump-phi0.3-n1000.h5.checkpoint"):
    with h5py.File(path) as h:
        return h["positions"][()], float(h["box_edge"][()]), float(h["strain"][()])
def pcg(A, b, x0, prec, tol, maxit=2000):
    x = x0.copy(); r = b - A @ x; bn = np.linalg.norm(b)
    if np.linalg.norm(r) <= tol*bn: return x, 0
    z = prec(r); p = z.copy(); rz = r @ z
    for it in range(1, maxit+1):
        q = A @ p; al = rz / (p @ q); x += al*p; r -= al*q
        if np.linalg.norm(r) <= tol*bn: return x, it
        z = prec(r); rz2 = r @ z; p = z + (rz2/rz)*p; rz = rz2
    return x, maxit
