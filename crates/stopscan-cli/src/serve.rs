//! `stopscan serve`: the transport around [`stopscan::pipeline::serve::Server`]: lines on
//! standard input and output, or on TCP connections one after another.

use std::io::BufReader;
use std::net::TcpListener;

use anyhow::Context;
use stopscan::pipeline::serve::{ServeOptions, Server, TransportError, serve_lines};

use crate::cli::{Global, ServeArgs};

pub(crate) fn run(a: &ServeArgs, _g: &Global) -> anyhow::Result<()> {
    let options = ServeOptions { max_scans: a.max_scans, fsync: a.fsync };
    let mut server = match (&a.journal, &a.resume) {
        (Some(j), None) => Server::with_journal(j, options)?,
        (None, Some(r)) => {
            let s = Server::resume(r, options)?;
            eprintln!(
                "resumed {} at step {}{}",
                r.display(),
                s.steps(),
                if s.is_done() { " (the session is over)" } else { "" }
            );
            s
        }
        _ => Server::new(options),
    };
    let Some(addr) = &a.listen else {
        let stdin = std::io::stdin();
        return Ok(serve_lines(&mut server, stdin.lock(), std::io::stdout().lock())?);
    };
    let listener = TcpListener::bind(addr).with_context(|| format!("cannot listen on {addr}"))?;
    eprintln!("listening on {}", listener.local_addr()?);
    for stream in listener.incoming() {
        let stream = match stream {
            Ok(s) => s,
            Err(e) => {
                eprintln!("connection failed: {e}");
                continue;
            }
        };
        // Replies are small and answer a waiting robot: send each at once.
        stream.set_nodelay(true)?;
        let reader = BufReader::new(stream.try_clone()?);
        match serve_lines(&mut server, reader, stream) {
            Ok(()) => {}
            // A journal that cannot be written ends the server; a dropped connection only
            // this connection.
            Err(TransportError::Serve(e)) => return Err(e.into()),
            Err(TransportError::Io(e)) => eprintln!("connection closed: {e}"),
        }
        if server.is_done() {
            break;
        }
    }
    Ok(())
}
