//! `stopscan serve`: the transport around [`stopscan::pipeline::serve::Server`]: lines on
//! standard input and output, or on TCP connections.
//!
//! On TCP the newest connection takes over: a robot whose link dropped may connect again
//! while its old connection still looks open to the server (a half-open socket after a Wi-Fi
//! loss), so the old one is shut down, its pending read ends, and the session goes on with
//! the new one.

use std::io::BufReader;
use std::net::{Shutdown, TcpListener, TcpStream};
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use anyhow::Context;
use stopscan::pipeline::serve::{ServeError, ServeOptions, Server, TransportError, serve_lines};

use crate::cli::{Global, ServeArgs};

pub(crate) fn run(a: &ServeArgs, _g: &Global) -> anyhow::Result<()> {
    let options = ServeOptions { max_scans: a.max_scans, fsync: a.fsync, record: a.mcap.is_some() };
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
        let served = serve_lines(&mut server, stdin.lock(), std::io::stdout().lock());
        // The recording is written however the session ended: it holds every step taken.
        write_mcap(&server, a.mcap.as_deref())?;
        return Ok(served?);
    };
    let listener = TcpListener::bind(addr).with_context(|| format!("cannot listen on {addr}"))?;
    eprintln!("listening on {}", listener.local_addr()?);
    listen(&listener, server, a.mcap.as_deref())
}

/// Writes the session's MCAP recording to `path`, when one was asked for.
fn write_mcap(server: &Server, path: Option<&std::path::Path>) -> anyhow::Result<()> {
    if let (Some(path), Some(bytes)) = (path, server.mcap()) {
        stopscan::io::atomic::write_bytes(path, &bytes?)?;
        eprintln!("wrote {}", path.display());
    }
    Ok(())
}

/// What the connections share: the session, the connection being served, and how the
/// server ends.
struct Shared {
    server: Mutex<Server>,
    /// The newest connection: its number and its stream.
    current: Mutex<Option<(u64, TcpStream)>>,
    /// The session is over and its robot closed the connection.
    finished: AtomicBool,
    /// The journal failed: the server must stop.
    failed: Mutex<Option<ServeError>>,
}

/// Serves connections until the session is over and its robot has gone, each new connection
/// taking over from the one before.
fn listen(
    listener: &TcpListener,
    server: Server,
    mcap: Option<&std::path::Path>,
) -> anyhow::Result<()> {
    listener.set_nonblocking(true)?;
    let shared = Arc::new(Shared {
        server: Mutex::new(server),
        current: Mutex::new(None),
        finished: AtomicBool::new(false),
        failed: Mutex::new(None),
    });
    let mut count = 0u64;
    loop {
        let server = || shared.server.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(e) = shared.failed.lock().unwrap_or_else(PoisonError::into_inner).take() {
            write_mcap(&server(), mcap)?;
            return Err(e.into());
        }
        if shared.finished.load(Ordering::SeqCst) {
            return write_mcap(&server(), mcap);
        }
        let stream = match listener.accept() {
            Ok((s, _)) => s,
            Err(e) if e.kind() == std::io::ErrorKind::WouldBlock => {
                std::thread::sleep(Duration::from_millis(20));
                continue;
            }
            Err(e) => {
                eprintln!("connection failed: {e}");
                continue;
            }
        };
        stream.set_nonblocking(false)?;
        // Replies are small and answer a waiting robot: send each at once.
        stream.set_nodelay(true)?;
        count += 1;
        let old = shared
            .current
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .replace((count, stream.try_clone()?));
        if let Some((_, old)) = old {
            eprintln!("a new connection takes over");
            let _ = old.shutdown(Shutdown::Both);
        }
        let shared = Arc::clone(&shared);
        let id = count;
        std::thread::spawn(move || serve_connection(&shared, id, &stream));
    }
}

fn serve_connection(shared: &Shared, id: u64, stream: &TcpStream) {
    let Ok(reader) = stream.try_clone().map(BufReader::new) else { return };
    // The session is served by one connection at a time: a newer one waits here until this
    // one's stream is shut down.
    let mut server = shared.server.lock().unwrap_or_else(PoisonError::into_inner);
    match serve_lines(&mut server, reader, stream) {
        Ok(()) => {}
        Err(TransportError::Serve(e)) => {
            *shared.failed.lock().unwrap_or_else(PoisonError::into_inner) = Some(e);
            return;
        }
        Err(TransportError::Io(e)) => eprintln!("connection closed: {e}"),
    }
    // Over, and this connection is still the newest (not replaced while it ended): done.
    let newest =
        shared.current.lock().unwrap_or_else(PoisonError::into_inner).as_ref().map(|c| c.0)
            == Some(id);
    if server.is_done() && newest {
        shared.finished.store(true, Ordering::SeqCst);
    }
}
