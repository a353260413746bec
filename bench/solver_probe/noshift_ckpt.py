# Copy of a checkpoint whose stored experiment has hydro.ic_shifts: [] (for A/B runs of the
# fallback without shifts from the same state; the checkpoint predates the key).
import h5py, sys, shutil, numpy as np
src, dst = sys.argv[1], sys.argv[2]
shutil.copy(src, dst)
with h5py.File(dst, 'r+') as h:
    e = h['experiment'][()].decode()
    e = e.replace("hydro: {plugin: fld", "hydro: {plugin: fld, ic_shifts: []", 1)
    del h['experiment']
    h['experiment'] = np.bytes_(e.encode())
