# Block IC of the dumped R in numpy: IC(0) on R's pattern plus cluster fill, in reverse
# Cuthill-McKee order or another, with Manteuffel's diagonal shift; iterations of each.
from probe import *
nz = np.linalg.norm(Ab, axis=(2, 3)) > 0; np.fill_diagonal(nz, False)
def rcm():
    deg=nz.sum(1); seen=np.zeros(N,bool); order=[]
    for s in np.argsort(deg):
        if seen[s]: continue
        seen[s]=True; q=[s]
        while q:
            i=q.pop(0); order.append(i)
            nb=[j for j in np.nonzero(nz[i])[0] if not seen[j]]
            for j in sorted(nb,key=lambda j:deg[j]): seen[j]=True; q.append(j)
    return np.array(order[::-1])
def clusters(th, maxc):
    """StiffClusterFill's fill: every pair inside a group of 3..maxc bodies joined above ratio th."""
    lab = components(ratio, th)[0]; fill = np.zeros((N, N), bool); sz = np.bincount(lab)
    for c in np.nonzero((sz >= 3) & (sz <= maxc))[0]:
        m = np.nonzero(lab == c)[0]; fill[np.ix_(m, m)] = True
    np.fill_diagonal(fill, False)
    return fill
def factor(order,pattern,shift=0.0):
    inv=np.empty(N,int); inv[order]=np.arange(N)
    P=pattern[np.ix_(order,order)]
    B=Ab[np.ix_(order,order)]
    W={}
    rows=[np.nonzero(P[k,k+1:])[0]+k+1 for k in range(N)]
    for k in range(N):
        W[(k,k)]=B[k,k]+shift*np.diag(np.diag(B[k,k]))
        for j in rows[k]: W[(k,j)]=B[k,j].copy()
    U={}
    for k in range(N):
        try: Lkk=np.linalg.cholesky(W[(k,k)])
        except np.linalg.LinAlgError: return None
        U[(k,k)]=Lkk.T
        Uk={j: np.linalg.solve(Lkk,W[(k,j)]) for j in rows[k]}
        U.update({(k,j):v for j,v in Uk.items()})
        js=rows[k]
        for a,i in enumerate(js):
            W[(i,i)]-=Uk[i].T@Uk[i]
            for j in js[a+1:]:
                if (i,j) in W: W[(i,j)]-=Uk[i].T@Uk[j]
    urow=[[(j,U[(k,j)]) for j in rows[k]] for k in range(N)]
    diag=[U[(k,k)] for k in range(N)]
    perm=(6*order[:,None]+np.arange(6)).ravel()
    def prec(r):
        y=r[perm].reshape(N,6).copy()
        # forward: U^T y = r  (U^T lower: row i gets sum_k<i U_ki^T y_k)
        for k in range(N):
            y[k]=np.linalg.solve(diag[k].T,y[k])
            for j,v in urow[k]: y[j]-=v.T@y[k]
        # backward: U z = y
        for k in range(N-1,-1,-1):
            acc=y[k].copy()
            for j,v in urow[k]: acc-=v@y[j]
            y[k]=np.linalg.solve(diag[k],acc)
        z=np.empty(n); z[perm]=y.ravel(); return z
    return prec
if __name__=="__main__":
    order=rcm()
    x,it=pcg(A,b,x0,Mi,tol); print("dumped factor: warm",it, "cold", pcg(A,b,0*x0,Mi,tol)[1], flush=True)
    configs=[("IC(0)",nz,24)]
    for th,mc in [(0.5,24),(0.4,24),(0.3,24),(0.3,64),(0.2,64)]:
        configs.append((f"fill ratio>{th} clusters<= {mc}", nz|clusters(th,mc), mc))
    for name,pat,_ in configs:
        extra=(pat&~nz).sum()//2
        for shift in [0.0,0.01,0.04,0.16]:
            pr=factor(order,pat,shift)
            if pr is None: print(f"{name} (+{extra} fill blocks) shift {shift}: breakdown", flush=True); continue
            print(f"{name} (+{extra} fill blocks) shift {shift}: warm {pcg(A,b,x0,pr,tol)[1]} cold {pcg(A,b,0*x0,pr,tol)[1]}", flush=True)
            break
