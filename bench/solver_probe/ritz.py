# Deflation with Ritz vectors recycled from a previous solve (Saad et al. 2000), on the dumped
# sheared-state system: solve 1 (b) stores its search directions; Ritz pairs of M^-1 A on their span
# (P^T A P y = theta P^T M P y); solve 2 (another right-hand side, same matrix) deflated with the k
# lowest (A-DEF2). Also the lowest Ritz values against the true eigenvalues.
from probe import *
Ms=(Minv+Minv.T)/2
M=np.linalg.inv(Ms)
ev=np.load(OUT+'/ev.npy')
def pcg_store(b,x0,maxit=500):
    x=x0.copy(); r=b-A@x; bn=np.linalg.norm(b); z=Ms@r; p=z.copy(); rz=r@z; P=[]
    for it in range(1,maxit+1):
        P.append(p.copy()); q=A@p; al=rz/(p@q); x+=al*p; r-=al*q
        if np.linalg.norm(r)<=tol*bn: return x,it,np.array(P).T
        z=Ms@r; rz2=r@z; p=z+(rz2/rz)*p; rz=rz2
    return x,maxit,np.array(P).T
rng=np.random.default_rng(1)
for label,start in [("cold",np.zeros(n)),("warm",x0)]:
    x,it,P=pcg_store(b,start)
    G=P.T@A@P; H=P.T@M@P
    L=np.linalg.cholesky(H); Li=np.linalg.inv(L)
    th,Y=np.linalg.eigh(Li@G@Li.T); Y=Li.T@Y
    print(f"solve 1 ({label}): {it} iterations; lowest Ritz values {np.round(th[:6],4)} (true {np.round(ev[:6],4)})")
    # solve 2: the same matrix, the right-hand side moved by 10 % (a next stage's)
    b2=b+0.1*np.linalg.norm(b)/np.sqrt(n)*rng.standard_normal(n)
    xs=x.copy() if label=="warm" else np.zeros(n)
    base=pcg(A,b2,xs,lambda r: Ms@r,tol)[1]
    out=[f"plain {base}"]
    for k in [1,2,4,8,12]:
        Z=P@Y[:,:k]
        prec=adef2(Z,lambda r: Ms@r); Ei=np.linalg.inv(Z.T@A@Z)
        s0=xs+Z@(Ei@(Z.T@(b2-A@xs)))
        out.append(f"k={k}: {pcg(A,b2,s0,prec,tol)[1]}")
    print(f"  solve 2 ({label} start):", ", ".join(out), flush=True)
