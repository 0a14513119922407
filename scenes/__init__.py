"""The built-in scenes (*.toml) and studies (studies/*.toml), installed as
the package data of ``hypercontact.scenes`` (see hypercontact.scene.builtin)."""
