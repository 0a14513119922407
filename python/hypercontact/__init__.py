"""hypercontact."""
