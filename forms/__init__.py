"""UFL forms of hypercontact: material laws ψ(F) and volume formulations.

Installed as the sub-package ``hypercontact.forms``.
"""
