"""hypercontact."""
import os

# PT-SCOTCH (dolfinx's mesh partitioner) splits a graph with as many threads
# as the machine has cores unless told otherwise, and the split then depends
# on the threads' timing: the same mesh built twice could be distributed
# differently, and a checkpoint (each rank's own part) no longer fitted the
# mesh it was resumed on. One thread makes the split a function of the mesh
# (with the seeded partitioner of _dolfinx.partitioner). Set before dolfinx
# loads SCOTCH; a user's own setting is kept.
os.environ.setdefault("SCOTCH_PTHREAD_NUMBER", "1")
